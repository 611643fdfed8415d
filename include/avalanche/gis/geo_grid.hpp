#pragma once
// A solver Grid with its coordinate reference system: the bridge between the
// solver (avalanche::Grid, j = 0 at the SOUTH row) and GIS files (north-up rasters,
// row 0 at the top). Coordinates are metres in a projected CRS.
#include <array>
#include <string>

#include "avalanche/core/grid.hpp"

namespace avalanche::gis {

struct GeoGrid {
    Grid grid;            // solver orientation, metres in crs_wkt
    std::string crs_wkt;  // WKT2 of a projected, metric CRS

    // North-up GDAL geotransform of the same cells:
    // {x0, dx, 0, y0 + ny*dy, 0, -dy} -- GeoTIFF row 0 is solver row j = ny-1.
    [[nodiscard]] std::array<double, 6> geotransform() const;
    // EPSG code of crs_wkt, or 0 when it has none (e.g. a custom proj string).
    [[nodiscard]] int epsg() const;
    // Human-readable name, e.g. "WGS 84 / UTM zone 32N (EPSG:32632)".
    [[nodiscard]] std::string crs_label() const;
};

// EPSG code of the UTM zone holding (lon, lat) in degrees (WGS 84):
// 32601..32660 north of the equator, 32701..32760 south of it. Zones are the
// regular 6-degree bands (the Norway/Svalbard exceptions are not applied).
// ConfigError("crs", ...) beyond 84 N / 80 S where UTM is not defined.
int utm_epsg_for(double lon, double lat);
// WKT2 of that UTM zone.
std::string utm_crs_wkt_for(double lon, double lat);

// WKT2 of a CRS given by a user ("EPSG:31287", WKT, PROJ string, ...).
// ConfigError(key, ...) if GDAL/PROJ cannot interpret it.
std::string crs_wkt_from_user(const std::string& text, const std::string& key = "crs");

// A CRS the user asks the grid to be in: ConfigError(key, ...) unless GDAL/PROJ can
// interpret it as a projected CRS in metres. Checked with the scenario, before any
// file is read or written.
void check_grid_crs(const std::string& text, const std::string& key);

}  // namespace avalanche::gis
