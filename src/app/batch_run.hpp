#pragma once
// `avalanche-hazard batch`: many scenarios from one base scenario (docs/batch.md).
#include <string>
#include <vector>

#include "commands.hpp"

namespace avalanche::detail {

struct BatchArguments {
    std::string scenario;             // base scenario file (required)
    std::vector<std::string> sweeps;  // "--sweep NAME=VALUES", repeatable
    std::string table;                // "--table FILE.csv" instead of sweeps
    std::string out;
    bool overwrite = false;
    int parallel = 0;  // scenarios at a time; 0 = number of cores
};

int run_batch(const BatchArguments& args, const GlobalOptions& global);

}  // namespace avalanche::detail
