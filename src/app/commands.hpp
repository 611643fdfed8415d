#pragma once
// One registration function per subcommand (PDAL keeps one class per kernel): each adds
// its options to the CLI11 app and returns the action to run after parsing.
#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>

#include "avalanche/app/scenario_overrides.hpp"

namespace avalanche::detail {

// The action of the chosen subcommand; returns the exit code.
using Command = std::function<int()>;

struct GlobalOptions {
    bool quiet = false;
    bool verbose = false;
    bool debug = false;
    std::string command_line;  // the whole invocation, for summary.json
};

Command add_run_command(CLI::App& app, const GlobalOptions& global);
// The scenario flags (--dem, --release, --delta, ...) of `run` and `batch`, filling `o`
// (scenario_flags.cpp).
void add_scenario_flags(CLI::App& cmd, ScenarioOverrides& o);
// The bundled default scene (scenarios/demo_avakot) run like `run --scenario`.
Command add_demo_command(CLI::App& app, const GlobalOptions& global);

// What `run` executes; `demo` fills it with the bundled scenario.
struct RunArguments {
    std::optional<std::string> scenario;
    std::string out;
    bool overwrite = false;
    int threads = 0;
    ScenarioOverrides overrides;
};
int execute_run(const RunArguments& args, const GlobalOptions& global);
Command add_version_command(CLI::App& app);
// Many scenarios from one base scenario (batch_run.cpp, docs/batch.md).
Command add_batch_command(CLI::App& app, const GlobalOptions& global);

}  // namespace avalanche::detail
