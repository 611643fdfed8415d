#include "void_fill.hpp"

#include <gdal_alg.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <exception>
#include <thread>

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

// GDALFillNodata's inverse-distance interpolation of the void cells (NaN in z) within
// max_distance cells of data, in bands of rows, one thread each. The interpolation of a
// cell reads valid cells at most max_distance rows away (its column trackers forget a
// value that many rows on) and max_distance columns away (its quadrant search steps no
// farther), so a band run with that many rows of context on either side gives its own
// rows the values a run over the whole grid gives them, to the bit. The bands are cut in
// GDAL's orientation (north up), in which the interpolation runs, and are at least as
// tall as the context. Cells it does not reach stay NaN. Returns the grid's values in
// the solver's orientation, interpolated cells filled.
std::vector<double> interpolate_near_data(const Grid& g, const std::vector<double>& z,
                                          double max_distance, int threads) {
    const int context = static_cast<int>(std::ceil(max_distance)) + 1;
    const int bands = std::max(1, std::min(threads, g.ny / context));
    std::vector<double> filled(z.size());
    // A band's failure (GDAL's, or memory) is rethrown here, not in its thread, where an
    // escaping exception would end the program.
    std::vector<std::exception_ptr> failure(static_cast<std::size_t>(bands));
    const auto fill_band = [&](int b) {
        // GDAL rows [r0, r1) are the band's, [c0, c1) the band with its context.
        const int r0 = g.ny * b / bands, r1 = g.ny * (b + 1) / bands;
        const int c0 = std::max(0, r0 - context), c1 = std::min(g.ny, r1 + context);
        const int rows = c1 - c0;
        const std::size_t n = static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(rows);
        std::vector<double> values(n);
        std::vector<std::uint8_t> valid(n);
        for (int r = c0; r < c1; ++r) {
            const double* from = z.data() + static_cast<std::size_t>(flipped_row(r, g.ny)) * g.nx;
            const std::size_t at = static_cast<std::size_t>(r - c0) * g.nx;
            std::copy_n(from, g.nx, values.begin() + static_cast<std::ptrdiff_t>(at));
            for (int i = 0; i < g.nx; ++i) valid[at + i] = std::isfinite(from[i]) ? 1 : 0;  // 0 = to fill
        }
        DatasetPtr v = create_mem_raster(g.nx, rows, 1, GDT_Float64);
        DatasetPtr m = create_mem_raster(g.nx, rows, 1, GDT_Byte);
        GDALRasterBand* vb = v->GetRasterBand(1);
        GDALRasterBand* mb = m->GetRasterBand(1);
        // Its working rasters (distance and value of the nearest data above each cell)
        // in memory, not GDAL's default of temporary GeoTIFFs on disk.
        CPLStringList options;
        options.SetNameValue("TEMP_FILE_DRIVER", "MEM");
        if (vb->RasterIO(GF_Write, 0, 0, g.nx, rows, values.data(), g.nx, rows, GDT_Float64, 0, 0,
                         nullptr) != CE_None ||
            mb->RasterIO(GF_Write, 0, 0, g.nx, rows, valid.data(), g.nx, rows, GDT_Byte, 0, 0,
                         nullptr) != CE_None ||
            GDALFillNodata(GDALRasterBand::ToHandle(vb), GDALRasterBand::ToHandle(mb), max_distance, 0,
                           0, options.List(), nullptr, nullptr) != CE_None ||
            vb->RasterIO(GF_Read, 0, r0 - c0, g.nx, r1 - r0, values.data(), g.nx, r1 - r0, GDT_Float64,
                         0, 0, nullptr) != CE_None)
            throw Error(ExitCode::internal, "GDALFillNodata failed on the DEM voids");
        for (int r = r0; r < r1; ++r)
            std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(r - r0) * g.nx, g.nx,
                        filled.begin() + static_cast<std::ptrdiff_t>(flipped_row(r, g.ny)) * g.nx);
    };
    const auto run_band = [&](int b) {
        try {
            fill_band(b);
        } catch (...) {
            failure[static_cast<std::size_t>(b)] = std::current_exception();
        }
    };
    std::vector<std::thread> team;
    for (int b = 1; b < bands; ++b) team.emplace_back(run_band, b);
    run_band(0);
    for (std::thread& t : team) t.join();
    for (const std::exception_ptr& e : failure)
        if (e) std::rethrow_exception(e);
    return filled;
}

}  // namespace

VoidFillResult fill_voids(const GeoGrid& geo, std::vector<double>& z, int threads) {
    VoidFillResult result;
    std::vector<bool> is_void(z.size());
    for (std::size_t k = 0; k < z.size(); ++k) is_void[k] = !std::isfinite(z[k]);
    result.origin = classify(geo.grid, is_void);
    for (std::uint8_t o : result.origin) {
        if (o == static_cast<std::uint8_t>(CellOrigin::filled_hole)) ++result.holes;
        if (o == static_cast<std::uint8_t>(CellOrigin::filled_outside)) ++result.outside;
    }
    if (result.holes + result.outside == 0) return result;

    // GDALFillNodata's cost grows with the search distance (40 s for 3.6 M cells with
    // 1.4 M voids when it spans the grid), so it interpolates near the data only; the
    // far voids, outside the footprint where no interpolation is meaningful, are then
    // extended layer by layer (extend_from_neighbours). Voids stay NaN so that a cell the
    // interpolation did not reach is detected below.
    const double max_distance =
        std::min(kInterpolationReachCells, static_cast<double>(geo.grid.nx + geo.grid.ny));
    const std::vector<double> filled = interpolate_near_data(geo.grid, z, max_distance, threads);
    for (std::size_t k = 0; k < z.size(); ++k)
        if (is_void[k]) z[k] = filled[k];
    extend_from_neighbours(geo.grid, z);
    for (double v : z)
        if (!std::isfinite(v)) throw Error(ExitCode::internal, "DEM void filling left a gap");
    return result;
}

}  // namespace avalanche::gis::detail
