#pragma once
// Release areas: polygons (any OGR format and CRS) or a thickness raster, put onto the
// solver grid as BED-NORMAL release thickness (m) per cell, solver orientation.
#include <optional>
#include <string>
#include <vector>

#include "avalanche/gis/dem.hpp"
#include "avalanche/gis/geo_grid.hpp"

namespace avalanche::gis {

struct ReleaseOptions {
    // One bed-normal thickness (m) for every polygon; excludes thickness_field.
    std::optional<double> thickness;
    // Attribute holding each polygon's bed-normal thickness (m). When neither this nor
    // `thickness` is given, a field named "thickness" (AvaFrame convention) is used.
    std::string thickness_field;
};

struct Release {
    std::vector<double> thickness;  // bed-normal thickness (m) per cell, 0 outside
    // 0 outside every polygon, else k = 1..features: the polygon owning the cell
    // (feature_labels[k-1]). Where polygons overlap, the thicker one owns the cell.
    std::vector<int> feature_id;
    int features = 0;
    std::vector<std::string> feature_labels;  // "layer 'relKot' feature 1 (KoT)"
    std::vector<int> feature_cells;           // cells owned per feature
    std::string description_of_steps;
};

// Cell-centre rule: a cell is released when its centre lies inside a polygon (holes
// excluded), as GDALRasterizeGeometries without ALL_TOUCHED. Geometries are
// reprojected to the grid CRS; a layer without a CRS is taken to be in the grid CRS.
// Throws InputError naming the file, layer, feature and field for: unreadable files
// (missing Shapefile sidecars), no feature, non-polygon or invalid geometries,
// polygons outside the grid or covering no cell centre, missing / non-numeric /
// non-positive thickness values; ConfigError("thickness") when no thickness is known.
Release rasterize_release_polygons(const std::string& path, const GeoGrid& geo,
                                   const ReleaseOptions& opts = {});

// A release-thickness raster (bed-normal m, any CRS) resampled onto the grid: average
// when the raster is finer than the grid (keeps the volume), bilinear otherwise.
// Nodata and cells outside the raster give 0. Negative values are refused, as is a
// raster giving no thickness on the grid.
std::vector<double> read_release_raster(const std::string& path, const GeoGrid& geo);

// Refuses (InputError naming release_path) a release on DEM cells that were filled
// voids, with the count.
void check_release_on_valid_dem(const Release& release, const Dem& dem,
                                const std::string& release_path = "release");
void check_release_on_valid_dem(const std::vector<double>& thickness, const Dem& dem,
                                const std::string& release_path = "release");

}  // namespace avalanche::gis
