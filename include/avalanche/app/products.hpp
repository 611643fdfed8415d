#pragma once
// The hazard products of a run (MODEL.md section 5) written into the output folder:
// GeoTIFF maps (COG) with a QGIS style and a quick-look PNG each, the computational
// DEM, monitoring-point series (CSV and HDF5) and a short Markdown report.
#include <cstdint>
#include <string>
#include <vector>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/app/shared_scene_products.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/output/hazard_maps.hpp"
#include "avalanche/output/monitoring.hpp"
#include "avalanche/output/run_caveats.hpp"
#include "avalanche/output/runout.hpp"

namespace avalanche {

// What the quick-looks' hatch means (gis::QuicklookShade), in the words both reports print
// under their maps when the run's DEM has cells outside its data.
inline constexpr const char* kNoTerrainDataNote =
    "Light grey hatched with diagonals is outside the DEM's data: the terrain there was "
    "filled in to run the model, and material that reaches it leaves the grid.";

struct ProductInputs {
    const PreparedScene& scene;  // its initial state may have moved into the simulation
    // Cells that held material at the start (interior, row-major, solver orientation).
    const std::vector<std::uint8_t>& release_cells;
    const Scenario& scenario;
    const HazardMaps& maps;
    const MonitoringPoints* probes;  // null without monitoring points
    const RunStatistics& stats;
    const RunoutMetrics& runout;
    // Why the maps may understate the hazard (reached the edge, not stopped); printed in
    // both reports as in the log and summary.json.
    const std::vector<RunCaveat>& caveats;
    std::string config_hash;
    std::string command_line;
    // The products this scene's other scenarios share (batch); null: made here alone.
    SharedSceneProducts* shared = nullptr;
};

// Writes every product; returns the file names written (relative to dir).
std::vector<std::string> write_products(const std::string& dir, const ProductInputs& in);

// DIR/report.md: what was run, the maps, the metrics, for a planner.
void write_report(const std::string& dir, const ProductInputs& in, const std::vector<std::string>& files);

}  // namespace avalanche
