#pragma once
// An observed deposit or affected area (polygons in any OGR format and CRS, e.g. a
// mapped avalanche outline) as a cell mask on the computational grid, for calibrating
// simulations against it (docs/batch.md, "Calibration against an observation").
#include <cstdint>
#include <string>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"

namespace avalanche::gis {

struct ObservedFootprint {
    std::vector<std::uint8_t> inside;  // 1 where the cell centre is inside a polygon, solver order
    std::size_t cells = 0;             // number of cells inside
    int polygons = 0;                  // polygon features read
    std::string description;           // one line for the log and calibration.json
};

// Same cell-centre rule as the release polygons (a cell belongs to the footprint when its
// centre lies inside a polygon, holes excluded); polygons are reprojected to the grid CRS,
// a layer without a CRS is taken to be in the grid CRS (so is every layer when the grid
// has none, as in the chute frame). Every layer of the file is read.
// Throws InputError naming the file for: an unreadable file, a file without polygon
// features, a non-polygon or invalid geometry, a polygon entirely outside the grid, and
// polygons covering no cell centre.
ObservedFootprint rasterize_observed_polygons(const std::string& path, const GeoGrid& geo);

}  // namespace avalanche::gis
