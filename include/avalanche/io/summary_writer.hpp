#pragma once
// DIR/summary.json: what a run did, in one small file a script can read (docs/io.md
// lists every key with its unit). All numbers come from the RunStatistics of the run.
#include <nlohmann/json.hpp>
#include <string>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

struct SummaryInputs {
    RunStatistics stats;
    nlohmann::json config;  // effective_config(scenario)
    std::string config_hash;
    std::string command_line;
    double h_min = 0.0;  // effective thin-layer depth (m)
    Grid grid;
    Frame frame = Frame::chute;
    std::size_t snapshots = 0;
    std::string results_file;  // file name of the snapshots, relative to the summary
};

nlohmann::json make_summary(const SummaryInputs& in);

// make_summary, pretty-printed, written atomically to `path`.
void write_summary(const std::string& path, const SummaryInputs& in);

}  // namespace avalanche
