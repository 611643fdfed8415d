#include "void_fill.hpp"

#include <gdal_alg.h>

#include <algorithm>
#include <cmath>
#include <deque>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/dem.hpp"
#include "orientation.hpp"

namespace avalanche::gis::detail {

namespace {

// Reach of the inverse-distance interpolation (cells): holes up to twice this across
// are interpolated from all sides.
constexpr double kInterpolationReachCells = 64.0;

// Void cells reachable from the grid border through void cells lie outside the DEM's
// footprint; the others are holes inside it. Four-neighbour flood fill.
std::vector<std::uint8_t> classify(const Grid& g, const std::vector<bool>& is_void) {
    std::vector<std::uint8_t> origin(g.cells(), static_cast<std::uint8_t>(CellOrigin::measured));
    std::deque<std::size_t> queue;
    auto index = [&](int i, int j) { return static_cast<std::size_t>(j) * g.nx + i; };
    auto seed = [&](int i, int j) {
        const std::size_t k = index(i, j);
        if (is_void[k] && origin[k] == 0) {
            origin[k] = static_cast<std::uint8_t>(CellOrigin::filled_outside);
            queue.push_back(k);
        }
    };
    for (int i = 0; i < g.nx; ++i) seed(i, 0), seed(i, g.ny - 1);
    for (int j = 0; j < g.ny; ++j) seed(0, j), seed(g.nx - 1, j);
    while (!queue.empty()) {
        const std::size_t k = queue.front();
        queue.pop_front();
        const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
        if (i > 0) seed(i - 1, j);
        if (i + 1 < g.nx) seed(i + 1, j);
        if (j > 0) seed(i, j - 1);
        if (j + 1 < g.ny) seed(i, j + 1);
    }
    for (std::size_t k = 0; k < origin.size(); ++k)
        if (is_void[k] && origin[k] == 0)
            origin[k] = static_cast<std::uint8_t>(CellOrigin::filled_hole);
    return origin;
}

// Gives every remaining non-finite cell the mean of its finite 8-neighbours, one ring of
// cells at a time (breadth-first from the known cells): O(cells), continuous, and flat
// far from the data. The grid holds at least one finite cell.
void extend_from_neighbours(const Grid& g, std::vector<double>& z) {
    std::vector<std::size_t> ring;
    auto known = [&](int i, int j) {
        return i >= 0 && j >= 0 && i < g.nx && j < g.ny &&
               std::isfinite(z[static_cast<std::size_t>(j) * g.nx + i]);
    };
    auto touches_known = [&](std::size_t k) {
        const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di)
                if ((di || dj) && known(i + di, j + dj)) return true;
        return false;
    };
    for (std::size_t k = 0; k < z.size(); ++k)
        if (!std::isfinite(z[k]) && touches_known(k)) ring.push_back(k);
    std::vector<bool> queued(z.size(), false);
    for (std::size_t k : ring) queued[k] = true;
    while (!ring.empty()) {
        std::vector<double> value(ring.size());
        for (std::size_t r = 0; r < ring.size(); ++r) {
            const int i = static_cast<int>(ring[r] % g.nx), j = static_cast<int>(ring[r] / g.nx);
            double sum = 0.0;
            int n = 0;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di)
                    if ((di || dj) && known(i + di, j + dj))
                        sum += z[static_cast<std::size_t>(j + dj) * g.nx + i + di], ++n;
            value[r] = sum / n;
        }
        for (std::size_t r = 0; r < ring.size(); ++r) z[ring[r]] = value[r];
        std::vector<std::size_t> next;
        for (std::size_t k : ring) {
            const int i = static_cast<int>(k % g.nx), j = static_cast<int>(k / g.nx);
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int a = i + di, b = j + dj;
                    if (a < 0 || b < 0 || a >= g.nx || b >= g.ny) continue;
                    const std::size_t m = static_cast<std::size_t>(b) * g.nx + a;
                    if (!queued[m] && !std::isfinite(z[m])) queued[m] = true, next.push_back(m);
                }
        }
        ring.swap(next);
    }
}

}  // namespace

VoidFillResult fill_voids(const GeoGrid& geo, std::vector<double>& z) {
    VoidFillResult result;
    std::vector<bool> is_void(z.size());
    std::vector<double> validity(z.size());
    for (std::size_t k = 0; k < z.size(); ++k) {
        is_void[k] = !std::isfinite(z[k]);
        validity[k] = is_void[k] ? 0.0 : 1.0;
    }
    result.origin = classify(geo.grid, is_void);
    for (std::uint8_t o : result.origin) {
        if (o == static_cast<std::uint8_t>(CellOrigin::filled_hole)) ++result.holes;
        if (o == static_cast<std::uint8_t>(CellOrigin::filled_outside)) ++result.outside;
    }
    if (result.holes + result.outside == 0) return result;

    // Voids stay NaN so that a cell the interpolation did not reach is detected below.
    DatasetPtr values = mem_from_solver_rows(geo, z, GDT_Float64);
    DatasetPtr mask = mem_from_solver_rows(geo, validity, GDT_Byte);  // 0 = to fill
    // GDALFillNodata's cost grows with the search distance (40 s for 3.6 M cells with
    // 1.4 M voids when it spans the grid), so it interpolates near the data only; the
    // far voids, outside the footprint where no interpolation is meaningful, are then
    // extended layer by layer (extend_from_neighbours).
    const double max_distance =
        std::min(kInterpolationReachCells, static_cast<double>(geo.grid.nx + geo.grid.ny));
    // Its working rasters (distance and value of the nearest data above each cell, the
    // grid's size) in memory, not GDAL's default of temporary GeoTIFFs on disk.
    CPLStringList options;
    options.SetNameValue("TEMP_FILE_DRIVER", "MEM");
    if (GDALFillNodata(GDALRasterBand::ToHandle(values->GetRasterBand(1)),
                       GDALRasterBand::ToHandle(mask->GetRasterBand(1)), max_distance, 0, 0,
                       options.List(), nullptr, nullptr) != CE_None)
        throw Error(ExitCode::internal, "GDALFillNodata failed on the DEM voids");
    std::vector<double> filled = read_solver_rows(*values, 1, geo.grid, "DEM void filling");
    for (std::size_t k = 0; k < z.size(); ++k)
        if (is_void[k]) z[k] = filled[k];
    extend_from_neighbours(geo.grid, z);
    for (double v : z)
        if (!std::isfinite(v)) throw Error(ExitCode::internal, "DEM void filling left a gap");
    return result;
}

}  // namespace avalanche::gis::detail
