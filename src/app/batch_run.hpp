#pragma once
// `avalanche-hazard batch`: many scenarios from one base scenario (docs/batch.md).
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"

namespace avalanche::detail {

struct BatchArguments {
    std::optional<std::string> scenario;  // base scenario file; or the flags below make one
    ScenarioOverrides overrides;          // run's scenario flags: file < flags < sweep values
    std::vector<std::string> sweeps;  // "--sweep NAME=VALUES", repeatable
    std::string table;                // "--table FILE.csv" instead of sweeps
    std::string out;
    bool overwrite = false;
    int parallel = 0;      // scenarios at a time (per MPI rank); 0 = its share of the cores
    std::string observed;  // "--observed FILE": polygons of an observed deposit
};

// One process, or one rank of an MPI launch (batch_mpi.hpp): rank 0 plans, decides the
// skips and writes every file of DIR; each rank runs its share of the scenarios.
int run_batch(const BatchArguments& args, const GlobalOptions& global);

}  // namespace avalanche::detail
