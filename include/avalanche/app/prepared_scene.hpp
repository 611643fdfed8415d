#pragma once
// A run in two steps (docs/cli.md):
//   prepare_scene: scenario -> grid, terrain coefficients, initial state and georeference
//                  (the chute frame here; the DEM frame in prepare_dem.cpp);
//   execute_scene: builds the Simulation, attaches the writers, runs, writes the outputs.
// Both frames share execute_scene, so every output is written the same way.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/io/scenario.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/output/monitoring.hpp"
#include "avalanche/output/runout.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

class SharedSceneProducts;  // shared_scene_products.hpp

struct PreparedScene {
    Grid grid;
    TerrainFields terrain;
    State initial;                         // at rest; h in the frame's thickness
    // A box that holds every cell of `initial` with material (zero outside it), from the
    // release; none: not known, the whole grid. Everything that reads the initial state
    // reads only this box (material_box), so that a small release on a large DEM
    // leaves the rest of the state's memory untouched.
    std::optional<ActiveBox> initial_box;
    std::array<double, 6> geotransform{};  // GDAL convention: row 0 at the top (max y)
    std::string crs_wkt;                   // empty in the chute frame
    Frame frame = Frame::chute;
    std::string description;  // one line for the log, e.g. "chute 60 x 40 m"
    std::vector<std::string> input_notes;  // what was read, reprojected, filled (log, report)

    // Monitoring points located on the grid (empty without [points]).
    std::vector<ProbeLocation> probes;
    // Cells outside the DEM's data footprint (filled, not measured terrain): material
    // that reaches them leaves the domain and is counted as outflow. Empty = none.
    std::vector<std::uint8_t> outside_data;
    // Horizontal (map) position of a cell for the runout metrics, and the horizontal
    // area of a cell (m^2).
    HorizontalPosition horizontal_position;
    double cell_area_m2 = 0.0;
    std::vector<std::string> input_files;  // inputs, for the report

    [[nodiscard]] ActiveBox material_box() const { return initial_box.value_or(ActiveBox{0, grid.nx, 0, grid.ny}); }
    // A copy of `initial` for one run of the scene (a batch's scenarios share it): with
    // initial_box, only its cells are written, the rest stays untouched zeros (on a large
    // DEM a copy of the whole state wrote 24 bytes per cell for every scenario).
    [[nodiscard]] State initial_copy() const;
};

// Dispatches on the terrain: ChuteGeometry here, DemTerrainSpec to prepare_dem_scene.
PreparedScene prepare_scene(const Scenario& s);

struct CheckpointContents;  // avalanche/io/checkpoint_file.hpp

struct RunOptions {
    std::string out_dir;       // must exist and be writable (prepare_output_folder)
    std::string command_line;  // recorded in summary.json
    // Called about every 0.1 s of wall time with the fraction done; false interrupts.
    std::function<bool(double)> progress;
    // DIR/checkpoint.h5 every this many simulated seconds (0: only when interrupted).
    double checkpoint_interval = 0.0;
    // Continue from this checkpoint (read_checkpoint) instead of t = 0; null = new run.
    const CheckpointContents* resume = nullptr;
    // Wall time the caller spent preparing the scene (prepare_scene), reported as the
    // run's "prepare" phase; negative: not this run's (batch runs share one scene).
    double prepare_seconds = -1.0;
    // What the scenarios of this scene share in their products (batch: the quick-looks'
    // shade, dem.tif); null for a run alone.
    SharedSceneProducts* shared_products = nullptr;
};

struct RunOutcome {
    RunStatistics stats;
    std::string results_path;
    std::string summary_path;
};

// Runs the scene and writes DIR/results.h5 and DIR/summary.json (atomically). The scene
// must outlive the call (the simulation reads its terrain in place). The simulation
// starts from scene.initial_copy() (`batch` runs several scenarios on one scene).
RunOutcome execute_scene(const PreparedScene& scene, const Scenario& s, const RunOptions& options);
// The same for a scene run once (`run`): scene.initial moves into the simulation
// instead of being copied, and is empty afterwards; the rest of the scene is kept.
RunOutcome execute_scene(PreparedScene&& scene, const Scenario& s, const RunOptions& options);

// What identifies the inputs of a run of `scene` started from `initial`: the scene
// fingerprint of its grid, terrain, initial state, sinks and monitoring cells
// (checkpoint_file.hpp). summary.json and the checkpoints record it; --resume and a
// resumed batch recompute a run whose inputs now prepare to another value.
std::string scene_fingerprint_of(const PreparedScene& scene, const State& initial);

// Output folder rules: refuses (OutputError, exit 4) a folder that already holds
// summary.json or results.h5, or the checkpoint of an unfinished run, unless
// `overwrite`; creates a missing folder; checks that it is writable before any work is
// done.
void prepare_output_folder(const std::string& dir, bool overwrite);

// Removes the files an earlier run wrote in `dir` (--overwrite): the fixed names
// (summary, results, checkpoints, reports, DEM, monitoring series) and the maps its
// summary lists with their styles and quick-looks; nothing else. So a run with fewer
// products, or one that fails, leaves none of the earlier run's beside its own.
void remove_previous_run(const std::string& dir);

}  // namespace avalanche
