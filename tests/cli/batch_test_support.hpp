#pragma once
// Helpers of the batch tests: the parametric chute at a coarse resolution (a few seconds
// per scenario on one core) and readers for the batch's CSV and the maps.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.hpp"

namespace avalanche::test {

// scenarios/parametric_chute/scenario.toml with 0.5 m cells, t_end 20 s, snapshots every 5 s.
inline const char* kCoarseParametricChute = R"(
[terrain]
type = "chute"
slope_deg = 45.0
length = 60.0
width = 40.0
transition = [25.0, 30.0]
runout_slope_deg = 0.0

[release]
shape = "cap"
center = [7.5, 20.0]
radius = 2.5

[material]
phi_deg = 35.0
delta_deg = 20.0

[numerics]
cell_size = 0.5
t_end = 20.0
output_interval = 5.0
)";

inline nlohmann::json read_json(const std::string& path) {
    std::ifstream f(path);
    return nlohmann::json::parse(f);
}

inline std::vector<std::string> split_csv(const std::string& line) {
    std::vector<std::string> out;
    std::string cell;
    for (char c : line) {
        if (c == ',') {
            out.push_back(cell);
            cell.clear();
        } else {
            cell += c;
        }
    }
    out.push_back(cell);
    return out;
}

// comparison.csv as rows of cells (row 0 = header).
inline std::vector<std::vector<std::string>> read_csv(const std::string& path) {
    std::vector<std::vector<std::string>> rows;
    for (const auto& line : lines_of(read_text(path))) rows.push_back(split_csv(line));
    return rows;
}

// Runs `command` (a whole shell command line, e.g. an mpirun launch of the binary) with
// stdout and stderr captured, like run_binary.
inline ProcessResult run_command(const ScratchDir& dir, const std::string& command) {
    const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
    const int status = std::system((command + " >'" + out + "' 2>'" + err + "'").c_str());
    ProcessResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
}

}  // namespace avalanche::test
