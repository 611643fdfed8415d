// Placeholder until the GIS layer provides the DEM frame: refuses DEM scenarios with a
// clear message. Replaced by the implementation that uses avalanche_gis.
#include "avalanche/app/prepare_dem.hpp"

#include "avalanche/core/error.hpp"

namespace avalanche {

PreparedScene prepare_dem_scene(const Scenario&) {
    throw ConfigError("terrain.type", "\"dem\" is not available in this build yet");
}

}  // namespace avalanche
