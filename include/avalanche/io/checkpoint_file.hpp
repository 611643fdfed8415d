#pragma once
// DIR/checkpoint.h5 and DIR/diagnostic_checkpoint.h5 (docs/io.md has the layout): the
// complete state of a run at a step boundary, so that `run --resume DIR` continues it
// bit for bit, and the last good / failing states of a numerical fault.
//
// A checkpoint appears atomically: it is written to "<path>.tmp", flushed, closed,
// fsync'ed and renamed over the previous one (and the folder is fsync'ed), so a
// SIGKILL at any moment leaves either the previous checkpoint or the new one.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/observer.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/io/scenario.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/output/monitoring.hpp"

namespace avalanche {

class ResultsWriter;

// What a resumed run needs besides the solver state: the effective configuration (to
// rebuild the scenario), the folder its relative paths start from, and a fingerprint
// of the prepared grid, terrain and initial state (to refuse changed inputs).
struct CheckpointInfo {
    nlohmann::json config;
    std::string config_hash;
    std::string working_dir;
    std::string scene_fingerprint;
    double checkpoint_interval = 0.0;  // s; 0 = only when interrupted
    int threads = 1;
    std::string software_version;
    std::string source_hash;  // of the program that wrote it (effective_config.hpp)
};

struct CheckpointContents {
    CheckpointInfo info;
    LoopState loop;
    int nx = 0, ny = 0, ghosts = 0;
    std::vector<double> h, hu, hv;  // with ghost cells, as Field2D::packed()
    CheckpointData observers;
    std::string path;
};

// Writes `path` atomically. `results`, if given, has its snapshots so far copied into
// the checkpoint (/results), so a resumed run rebuilds results.h5 without duplicates.
void write_checkpoint(const std::string& path, const CheckpointInfo& info,
                      const SimulationCheckpoint& c, const Grid& grid,
                      const ResultsWriter* results);

// The last good state (as a checkpoint, without snapshots) and the failing state
// (/failing_state), with the fault message.
void write_diagnostic_checkpoint(const std::string& path, const CheckpointInfo& info,
                                 const FaultReport& f, const Grid& grid);

// Reads a checkpoint written by write_checkpoint. Throws InputError naming the file and
// what is wrong (missing, not HDF5, not a checkpoint, truncated, wrong sizes).
CheckpointContents read_checkpoint(const std::string& path);

// Hex digest (64 bit: FNV-1a, the grid-sized arrays a word at a time in four lanes) of
// the prepared scene: grid geometry, every terrain field, the initial state, the sink
// mask and the monitoring-point cells. Of the initial state, `holding` (a box that holds
// every cell with material, which are zero outside it) and its cells: a small release
// on a large DEM does not read the rest of the state (on an ASTER-size tile, 0.4 s of
// page faults a run).
std::string scene_fingerprint(const Grid& grid, const TerrainFields& terrain, const State& initial,
                              const ActiveBox& holding, const std::vector<std::uint8_t>& sinks,
                              const std::vector<ProbeLocation>& probes);

// The scenario recorded in a checkpoint (its effective configuration), parsed and
// validated like a scenario file; paths stay as recorded (relative ones are relative to
// CheckpointInfo::working_dir). The caller compares config hashes.
Scenario scenario_from_config(const nlohmann::json& config, const std::string& label);

}  // namespace avalanche
