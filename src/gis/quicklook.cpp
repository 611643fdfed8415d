// Hillshade and the PNG quick-look.
#include "avalanche/gis/quicklook.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <utility>

#include "avalanche/core/error.hpp"
#include "orientation.hpp"

namespace avalanche::gis {

namespace {
constexpr double kShadeFloor = 0.35;  // darkest terrain tone under a coloured cell
constexpr double kOverlayOpacity = 0.85;
}  // namespace

std::vector<double> hillshade(const Grid& g, const std::vector<double>& z, double azimuth_deg,
                              double altitude_deg) {
    if (z.size() != g.cells()) throw Error(ExitCode::internal, "hillshade: size mismatch");
    const double az = azimuth_deg * std::numbers::pi / 180.0;
    const double alt = altitude_deg * std::numbers::pi / 180.0;
    // Unit vector towards the light in (east, north, up): azimuth 315 = from north-west.
    const double lx = std::sin(az) * std::cos(alt), ly = std::cos(az) * std::cos(alt),
                 lz = std::sin(alt);
    auto at = [&](int i, int j) {
        i = std::clamp(i, 0, g.nx - 1), j = std::clamp(j, 0, g.ny - 1);
        return z[static_cast<std::size_t>(j) * g.nx + i];
    };
    std::vector<double> shade(z.size());
    for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
            // Horn: weighted central differences over the 3x3 window (j + 1 is north).
            const double dzdx = ((at(i + 1, j + 1) + 2 * at(i + 1, j) + at(i + 1, j - 1)) -
                                 (at(i - 1, j + 1) + 2 * at(i - 1, j) + at(i - 1, j - 1))) /
                                (8.0 * g.dx);
            const double dzdy = ((at(i - 1, j + 1) + 2 * at(i, j + 1) + at(i + 1, j + 1)) -
                                 (at(i - 1, j - 1) + 2 * at(i, j - 1) + at(i + 1, j - 1))) /
                                (8.0 * g.dy);
            // Surface normal (-dz/dx, -dz/dy, 1), normalised, dotted with the light.
            const double n = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
            const double s = (-dzdx * lx - dzdy * ly + lz) / n;
            shade[static_cast<std::size_t>(j) * g.nx + i] = std::clamp(s, 0.0, 1.0);
        }
    }
    return shade;
}

int quicklook_cells_per_pixel(const Grid& grid) {
    const int longest = std::max(grid.nx, grid.ny);
    return std::max(1, (longest + kQuicklookMaxPixels - 1) / kQuicklookMaxPixels);
}

namespace {

// Whether the map gives the cell a value to colour (else only the hillshade shows).
bool has_value(double v, double nodata) { return v != nodata && std::isfinite(v); }

// The grid of a quick-look's pixels: blocks of f x f cells of g.
Grid pixel_grid(const Grid& g, int f) {
    Grid p = g;
    p.nx = (g.nx + f - 1) / f;
    p.ny = (g.ny + f - 1) / f;
    p.dx = g.dx * f;
    p.dy = g.dy * f;
    return p;
}

// Calls visit(b, j0, j1, i0, i1) for each block b of f x f cells of g (index
// bj * nx + bi on pixel_grid(g, f)): rows [j0, j1), columns [i0, i1), the blocks at
// the east and north edges cut short.
template <class Visit>
void for_each_block(const Grid& g, int f, Visit&& visit) {
    const Grid p = pixel_grid(g, f);
    for (int bj = 0; bj < p.ny; ++bj) {
        const int j0 = bj * f, j1 = std::min(j0 + f, g.ny);
        for (int bi = 0; bi < p.nx; ++bi) {
            const int i0 = bi * f, i1 = std::min(i0 + f, g.nx);
            visit(static_cast<std::size_t>(bj) * p.nx + bi, j0, j1, i0, i1);
        }
    }
}

// Per block of f x f cells (f > 1) the `block` of its valid values (nodata when none is).
std::vector<double> values_in_blocks(const Grid& g, const std::vector<double>& values, double nodata,
                                     QuicklookBlock block, int f) {
    std::vector<double> out(pixel_grid(g, f).cells());
    const bool largest = block == QuicklookBlock::maximum;
    for_each_block(g, f, [&](std::size_t b, int j0, int j1, int i0, int i1) {
        double chosen = nodata;
        bool any = false;
        for (int j = j0; j < j1; ++j)
            for (int i = i0; i < i1; ++i) {
                const double v = values[static_cast<std::size_t>(j) * g.nx + i];
                if (!has_value(v, nodata)) continue;
                if (!any || (largest ? v > chosen : v < chosen)) chosen = v;
                any = true;
            }
        out[b] = chosen;
    });
    return out;
}

}  // namespace

void write_quicklook_png(const std::string& path, const GeoGrid& geo,
                         const std::vector<double>& values, const std::vector<double>& elevation,
                         const ColorRamp& ramp, double nodata, QuicklookBlock block) {
    if (elevation.size() != geo.grid.cells())
        throw OutputError(path, "map and elevation sizes differ from the grid");
    write_quicklook_png_over(path, geo, values, quicklook_shade(geo.grid, hillshade(geo.grid, elevation)), ramp,
                             nodata, block);
}

QuicklookShade quicklook_shade(const Grid& g, std::vector<double> shade_of_cells,
                               const std::vector<std::uint8_t>& outside_data) {
    if (shade_of_cells.size() != g.cells() ||
        (!outside_data.empty() && outside_data.size() != g.cells()))
        throw Error(ExitCode::internal, "quicklook_shade: size mismatch");
    QuicklookShade q;
    q.cells_per_pixel = quicklook_cells_per_pixel(g);
    const int f = q.cells_per_pixel;
    if (!outside_data.empty()) {
        // A pixel without terrain data: all of its cells outside the footprint (a block
        // with one measured cell shows that cell's terrain).
        q.no_data.assign(pixel_grid(g, f).cells(), 1);
        for_each_block(g, f, [&](std::size_t b, int j0, int j1, int i0, int i1) {
            for (int j = j0; j < j1; ++j)
                for (int i = i0; i < i1; ++i)
                    if (outside_data[static_cast<std::size_t>(j) * g.nx + i] == 0) q.no_data[b] = 0;
        });
    }
    if (f == 1) {
        q.tone = std::move(shade_of_cells);
        return q;
    }
    // The mean of each block's cells, summed row by row.
    q.tone.resize(pixel_grid(g, f).cells());
    for_each_block(g, f, [&](std::size_t b, int j0, int j1, int i0, int i1) {
        double tone = 0.0;
        for (int j = j0; j < j1; ++j)
            for (int i = i0; i < i1; ++i) tone += shade_of_cells[static_cast<std::size_t>(j) * g.nx + i];
        q.tone[b] = tone / static_cast<double>((j1 - j0) * (i1 - i0));
    });
    return q;
}

void write_quicklook_png_over(const std::string& path, const GeoGrid& geo,
                              const std::vector<double>& values_of_cells,
                              const std::vector<double>& shade_of_cells, const ColorRamp& ramp,
                              double nodata, QuicklookBlock block) {
    if (values_of_cells.size() != geo.grid.cells() || shade_of_cells.size() != geo.grid.cells())
        throw OutputError(path, "map and hillshade sizes differ from the grid");
    write_quicklook_png_over(path, geo, values_of_cells, quicklook_shade(geo.grid, shade_of_cells), ramp,
                             nodata, block);
}

void write_quicklook_png_over(const std::string& path, const GeoGrid& geo,
                              const std::vector<double>& values_of_cells, const QuicklookShade& pixels,
                              const ColorRamp& ramp, double nodata, QuicklookBlock block) {
    detail::GdalErrorScope errors;
    const int f = quicklook_cells_per_pixel(geo.grid);
    const Grid g = f > 1 ? pixel_grid(geo.grid, f) : geo.grid;
    if (values_of_cells.size() != geo.grid.cells() || pixels.cells_per_pixel != f ||
        pixels.tone.size() != g.cells())
        throw OutputError(path, "map and hillshade sizes differ from the grid");
    std::vector<double> blocks;
    if (f > 1) blocks = values_in_blocks(geo.grid, values_of_cells, nodata, block, f);
    const std::vector<double>& values = f > 1 ? blocks : values_of_cells;
    if (!pixels.no_data.empty() && pixels.no_data.size() != g.cells())
        throw OutputError(path, "map and hillshade sizes differ from the grid");
    std::vector<std::uint8_t> rgb[3];
    for (auto& c : rgb) c.resize(g.cells());
    for (std::size_t k = 0; k < g.cells(); ++k) {
        const bool no_data = !pixels.no_data.empty() && pixels.no_data[k] != 0;
        const double shade =
            no_data ? no_data_tone(static_cast<int>(k % static_cast<std::size_t>(g.nx)),
                                   static_cast<int>(k / static_cast<std::size_t>(g.nx)))
                    : pixels.tone[k];
        const double grey = 255.0 * shade;
        Rgba c{0, 0, 0, 0};
        if (has_value(values[k], nodata)) c = color_at(ramp, values[k]);
        const double a = kOverlayOpacity * c.a / 255.0;
        const double tone = kShadeFloor + (1.0 - kShadeFloor) * shade;
        const double channel[3] = {double(c.r), double(c.g), double(c.b)};
        for (int b = 0; b < 3; ++b)
            rgb[b][k] = static_cast<std::uint8_t>(
                std::clamp(std::round(a * channel[b] * tone + (1.0 - a) * grey), 0.0, 255.0));
    }
    // No geotransform or CRS: a plain picture, so the PNG driver writes no .aux.xml.
    detail::DatasetPtr mem = detail::create_mem_raster(g.nx, g.ny, 3, GDT_Byte);
    for (int b = 0; b < 3; ++b) detail::write_solver_rows(*mem, b + 1, g, rgb[b]);

    GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
    if (png == nullptr) throw OutputError(path, "GDAL has no PNG driver");
    const std::string part = path + ".part";
    std::error_code ec;
    bool written = false;
    {
        // zlib level 3 instead of the driver's 6: half the encoding time of a large
        // picture (0.41 -> 0.18 s for 1756 x 2068 cells) and no larger a file (level 3
        // took 1.4 % less on that scene, docs/performance.md, "Outside the solver").
        const char* const options[] = {"ZLEVEL=3", nullptr};
        detail::DatasetPtr out(png->CreateCopy(part.c_str(), mem.get(), FALSE,
                                               const_cast<char**>(options), nullptr, nullptr));
        written = out != nullptr;
    }
    if (!written || errors.failed()) {
        std::filesystem::remove(part, ec);
        throw OutputError(path, "cannot write the PNG" + errors.reason());
    }
    std::filesystem::rename(part, path, ec);
    if (ec) {
        const std::string why = ec.message();
        std::filesystem::remove(part, ec);
        throw OutputError(path, "cannot rename " + part + " into place: " + why);
    }
}

}  // namespace avalanche::gis
