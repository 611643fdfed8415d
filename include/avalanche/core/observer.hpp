#pragma once
// Observers watch the time loop (maxima, arrival times, mass balance, monitoring
// points, snapshots, checkpoints) without the loop knowing what they do.
#include <cstdint>

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
};

}  // namespace avalanche
