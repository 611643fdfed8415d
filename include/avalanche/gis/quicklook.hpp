#pragma once
// PNG quick-looks: a product map coloured over a hillshade of the terrain, for
// reports and a first glance without a GIS.
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

// Writes an RGB PNG (north at the top, one pixel per cell): grey hillshade, with
// `values` coloured by `ramp` where they differ from `nodata` and the ramp draws them.
// Written through GDAL's PNG driver (MEM dataset + CreateCopy) to "<path>.part", then
// renamed. OutputError on failure or size mismatch.
void write_quicklook_png(const std::string& path, const GeoGrid& geo,
                         const std::vector<double>& values, const std::vector<double>& elevation,
                         const ColorRamp& ramp, double nodata);
// The same over a hillshade computed once by the caller (hillshade above), for several
// maps of one terrain: `shade` in [0, 1], one value per cell.
void write_quicklook_png_over(const std::string& path, const GeoGrid& geo,
                              const std::vector<double>& values, const std::vector<double>& shade,
                              const ColorRamp& ramp, double nodata);

}  // namespace avalanche::gis
