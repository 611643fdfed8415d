#pragma once
// One registration function per subcommand (PDAL keeps one class per kernel): each adds
// its options to the CLI11 app and returns the action to run after parsing.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

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
Command add_version_command(CLI::App& app);

}  // namespace avalanche::detail
