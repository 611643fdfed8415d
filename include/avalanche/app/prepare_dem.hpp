#pragma once
// The DEM frame's scene preparation: DEM tiles -> grid and slope-consistent terrain
// coefficients, release polygons/raster -> initial state, CRS and geotransform.
// Defined in src/app/prepare_dem.cpp (which links avalanche_gis when it exists).
#include "avalanche/app/prepared_scene.hpp"

namespace avalanche {

PreparedScene prepare_dem_scene(const Scenario& s);

}  // namespace avalanche
