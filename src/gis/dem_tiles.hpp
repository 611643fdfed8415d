#pragma once
// Private: DEM tiles as opened and checked, and the choice of the target grid.
#include <array>
#include <string>
#include <vector>

#include "avalanche/gis/dem.hpp"
#include "gdal_support.hpp"

namespace avalanche::gis::detail {

struct DemTile {
    std::string path;
    DatasetPtr ds;
    OGRSpatialReference srs;          // traditional axis order; from the file or DemOptions
    std::array<double, 6> gt{};       // geotransform of the file
    long long valid_cells = 0;        // finite, not nodata
    long long void_cells = 0;         // nodata, NaN or Inf
    double z_min = 0.0, z_max = 0.0;  // over the valid cells
};

// Opens a tile (header only): names the file when it is not a raster or has no
// georeferencing or CRS.
DemTile open_dem_tile(const std::string& path, const OGRSpatialReference& user_crs,
                      const GdalErrorScope& errors);

// Reads an opened tile once in full (after the grid passed the memory check): names
// the file when it cannot be read to the end (truncated, corrupt), holds no valid
// elevation or has undeclared void markers.
void scan_dem_tile(DemTile& tile);

struct GridPlan {
    GeoGrid geo;
    bool same_as_source = false;  // target cells coincide with every tile's cells
    std::string crs_reason;       // why this CRS, for the description
};

// The target CRS, cell size and extent covering all tiles, checked against the
// memory limit (InputError naming the DEM files and the estimate).
GridPlan plan_dem_grid(const std::vector<DemTile>& tiles, const OGRSpatialReference& user_crs,
                       const DemOptions& opts);

}  // namespace avalanche::gis::detail
