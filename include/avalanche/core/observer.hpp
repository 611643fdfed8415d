#pragma once
// Observers watch the time loop (maxima, arrival times, mass balance, monitoring
// points, snapshots, checkpoints) without the loop knowing what they do.
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

struct SimulationView {
    const Grid& grid;
    const TerrainFields& terrain;
    const State& state;
    double t;              // simulated time (s)
    std::uint64_t step;    // steps taken
    const ActiveBox& box;  // cells that may be non-zero (everything outside is dry)
    // The boxes outside which the last step changed no cell (Stepper::bands: empty
    // cells and settled films are given back unchanged); empty: any cell of the box
    // may have changed (before the first step, or a view made elsewhere).
    std::span<const ActiveBox> changed = {};
};

// What an observer carries from step to step, as named plain arrays, so that a
// checkpoint can hold it without the core knowing any file format (src/io writes
// these as HDF5 datasets, docs/io.md). Names are "observer/quantity".
struct CheckpointData {
    std::map<std::string, std::vector<double>> reals;
    std::map<std::string, std::vector<std::int64_t>> integers;

    // The array `name`; throws InputError("checkpoint", ...) when it is missing or,
    // for expected_size >= 0, has another length: a checkpoint that does not match
    // the run must never be half-restored.
    [[nodiscard]] const std::vector<double>& real(const std::string& name, long long expected_size = -1) const;
    [[nodiscard]] const std::vector<std::int64_t>& integer(const std::string& name,
                                                           long long expected_size = -1) const;
};

class StepObserver {
public:
    virtual ~StepObserver() = default;
    virtual void on_start(const SimulationView&) {}
    // After every step.
    virtual void on_step(const SimulationView&) {}
    // At t = 0, at every output_interval (hit exactly) and at the end.
    virtual void on_output(const SimulationView&) {}
    virtual void on_end(const SimulationView&) {}

    // Checkpoints: everything the observer has accumulated since on_start that its
    // later callbacks depend on, so that restore() + the remaining steps give exactly
    // what an uninterrupted run gives. Observers without running state keep the
    // defaults.
    virtual void save(CheckpointData&) const {}
    virtual void restore(const CheckpointData&) {}
};

}  // namespace avalanche
