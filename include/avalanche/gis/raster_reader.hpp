#pragma once
// Reading a north-up single-band raster (our own GeoTIFF products, typically) back onto
// a solver Grid: the batch command builds its envelopes from the maps each scenario
// wrote, so resumed and freshly computed scenarios go through the same path.
#include <optional>
#include <string>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"

namespace avalanche::gis {

struct RasterData {
    GeoGrid geo;                   // grid from the geotransform, CRS as WKT ("" = none)
    std::vector<double> values;    // band 1, solver orientation (index j*nx + i, j = 0 south)
    std::optional<double> nodata;  // the band's nodata value, if it has one
    std::string description, units;
};

// Throws InputError naming the file when it cannot be read, or when it is rotated or
// not north-up (the solver grid has no rotation).
RasterData read_geotiff(const std::string& path);

}  // namespace avalanche::gis
