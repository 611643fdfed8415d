#pragma once
// PNG quick-looks: a product map coloured over a hillshade of the terrain, for
// reports and a first glance without a GIS.
#include <cstdint>
#include <string>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"
#include "avalanche/gis/style.hpp"

namespace avalanche::gis {

// Hillshade in [0, 1] of an elevation field (m, solver orientation), Horn's (1981)
// 3x3 gradients, light from `azimuth_deg` (clockwise from north) at `altitude_deg`
// above the horizon; edge cells use one-sided differences. Flat ground gives
// sin(altitude).
std::vector<double> hillshade(const Grid& grid, const std::vector<double>& elevation,
                              double azimuth_deg = 315.0, double altitude_deg = 45.0);

// The longest side of a quick-look, in pixels: about a screen's width. A grid longer
// than this is drawn with an integer number of cells per pixel (quicklook_cells_per_pixel).
// The quick-look is a preview (the report shows it about 640 px wide); the GeoTIFF
// holds every cell. On a 1756 x 2068 grid the PNGs at one pixel per cell were half of
// the products' time and 11 of report.html's 14 MB (docs/performance.md, "Quick-looks").
inline constexpr int kQuicklookMaxPixels = 2048;

// Cells per pixel side of a grid's quick-look: 1 up to kQuicklookMaxPixels cells on the
// longest side, else the smallest integer that brings it within that.
[[nodiscard]] int quicklook_cells_per_pixel(const Grid& grid);

// What one pixel of a quick-look drawn in blocks of cells shows of its cells' values.
enum class QuicklookBlock {
    maximum,  // the largest valid value (depths, speeds, pressures, classes, frequencies)
    minimum,  // the smallest valid value (arrival times: the earliest)
};

// Writes an RGB PNG (north at the top): grey hillshade, with `values` coloured by
// `ramp` where they differ from `nodata` and the ramp draws them. One pixel per cell
// up to kQuicklookMaxPixels cells on the grid's longest side; beyond, each pixel is a
// block of f x f cells (f = quicklook_cells_per_pixel; the blocks at the east and north
// edges may be cut short), coloured by `block` of its cells' valid values (no colour
// when it has none) over the mean of its hillshade, so that a flow one cell wide still
// shows. Written through GDAL's PNG driver (MEM dataset + CreateCopy) to
// "<path>.part", then renamed. OutputError on failure or size mismatch.
void write_quicklook_png(const std::string& path, const GeoGrid& geo,
                         const std::vector<double>& values, const std::vector<double>& elevation,
                         const ColorRamp& ramp, double nodata,
                         QuicklookBlock block = QuicklookBlock::maximum);
// The same over a hillshade computed once by the caller (hillshade above), for several
// maps of one terrain: `shade` in [0, 1], one value per cell.
void write_quicklook_png_over(const std::string& path, const GeoGrid& geo,
                              const std::vector<double>& values, const std::vector<double>& shade,
                              const ColorRamp& ramp, double nodata,
                              QuicklookBlock block = QuicklookBlock::maximum);

// A hillshade as the quick-looks of a grid draw it: per pixel, the cell's tone (one
// pixel per cell) or the mean of its block of f x f cells. Made once for several maps,
// it spares each quick-look the pass over the cells' hillshade, and the cells' hillshade
// need not outlive it (on a 14.5 M-cell grid, 116 MB against 1.3 MB).
// Pixels with no terrain data (every cell of theirs outside the source DEM's data
// footprint, where the grid's elevations were filled in to run the model) are drawn as a
// flat light grey hatched with darker diagonals instead of their hillshade: the
// interpolated terrain there is not terrain anyone measured, and its hillshade (streaks,
// and steps along the footprint) would read as if it were.
struct QuicklookShade {
    int cells_per_pixel = 1;            // f, quicklook_cells_per_pixel of the grid
    std::vector<double> tone;           // per pixel, in [0, 1]
    std::vector<std::uint8_t> no_data;  // per pixel, 1 where no terrain data; empty: none
};
// `outside_data`: one flag per cell (1 outside the DEM's data), or empty when every cell
// has data.
[[nodiscard]] QuicklookShade quicklook_shade(const Grid& grid, std::vector<double> shade_of_cells,
                                             const std::vector<std::uint8_t>& outside_data = {});
// The grey (in [0, 1]) of a pixel without terrain data at pixel column i and row j (any
// orientation): the hatch's diagonal lines, one pixel wide every kNoDataHatchPeriod
// pixels, and the light ground between them.
inline constexpr int kNoDataHatchPeriod = 6;
inline constexpr double kNoDataGround = 0.93, kNoDataLine = 0.72;
[[nodiscard]] inline double no_data_tone(int i, int j) {
    return (i + j) % kNoDataHatchPeriod == 0 ? kNoDataLine : kNoDataGround;
}
// write_quicklook_png_over with the pixels' shade of quicklook_shade(geo.grid, ...).
void write_quicklook_png_over(const std::string& path, const GeoGrid& geo,
                              const std::vector<double>& values, const QuicklookShade& shade,
                              const ColorRamp& ramp, double nodata,
                              QuicklookBlock block = QuicklookBlock::maximum);

}  // namespace avalanche::gis
