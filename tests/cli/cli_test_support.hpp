#pragma once
// Helpers of the command-line tests: a scratch folder, a small fast chute scenario, and
// the binary run as a child process with its exit code, stdout and stderr.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/scratch_dir.hpp"

namespace avalanche::test {

// 10 m x 4 m chute of 0.5 m cells, a box release away from the edges: runs in well under
// a second, with no outflow (so the mass balance is exact to round-off).
inline const char* kSmallChute = R"(
[terrain]
type = "chute"
slope_deg = 35.0
length = 10.0
width = 4.0

[release]
shape = "box"
x = [1.0, 3.0]
y = [1.5, 2.5]
thickness = 0.5

[material]
phi_deg = 35.0
delta_deg = 20.0

[numerics]
cell_size = 0.5
t_end = 0.5
output_interval = 0.25
)";

inline std::string read_text(const std::string& path) {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
}

inline std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream s(text);
    for (std::string line; std::getline(s, line);) out.push_back(line);
    return out;
}

struct ProcessResult {
    int exit_code = -1;
    std::string out, err;
};

// Runs the binary with `args` (already shell-quoted where needed).
inline ProcessResult run_binary(const ScratchDir& dir, const std::string& args) {
    const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
    const std::string cmd =
        std::string("'") + AVALANCHE_BINARY + "' " + args + " >'" + out + "' 2>'" + err + "'";
    const int status = std::system(cmd.c_str());
    ProcessResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
}

}  // namespace avalanche::test
