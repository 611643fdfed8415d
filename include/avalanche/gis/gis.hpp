#pragma once
// The GIS layer (avalanche_gis): everything that reads or writes geodata.
#include "avalanche/gis/dem.hpp"
#include "avalanche/gis/geo_grid.hpp"
#include "avalanche/gis/points.hpp"
#include "avalanche/gis/quicklook.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "avalanche/gis/release.hpp"
#include "avalanche/gis/style.hpp"
