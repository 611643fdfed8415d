#pragma once
// The time loop: dt from the CFL rule (capped to hit output times and t_end), one
// Strang step, NaN/negative-depth detection, observers, and the end-of-run rule
// (MODEL.md 2.7): the run ends at t_end, or earlier when the flow has stopped:
//   - every cell at rest (all velocities exactly zero after friction), or
//   - total kinetic energy below stop_ke_fraction x its running maximum,
//     continuously for stop_duration seconds.
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/observer.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/numerics/stepper.hpp"
#include "avalanche/physics/material.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

enum class EndReason { end_time, stopped_at_rest, stopped_kinetic_energy, no_material, interrupted };
std::string to_string(EndReason r);

struct RunStatistics {
    EndReason end_reason = EndReason::end_time;
    double simulated_time = 0.0;  // s
    std::uint64_t steps = 0;
    std::uint64_t cell_updates = 0;
    double wall_seconds = 0.0;
    int threads = 1;
    double released_volume = 0.0;  // m^3 at t = 0
    double final_volume = 0.0;     // m^3 in the domain at the end
    double outflow_volume = 0.0;   // m^3 through open edges
    double max_kinetic_energy = 0.0;  // J/kg x m^3 (sum of h |u|^2 / 2 dA)
    [[nodiscard]] double relative_mass_error() const;
    [[nodiscard]] double cell_updates_per_second() const;
};

// Volume held by the state (m^3), summed in long double so that the mass balance
// is judged on the solver's round-off, not the diagnostic's.
double total_volume(const State& s, const Grid& g);

// Throws NumericalError naming the first non-finite or negative cell in the box.
void check_state(const State& s, const Grid& g, const ActiveBox& box, double t);

class Simulation {
public:
    Simulation(Grid grid, const TerrainFields& terrain, MaterialParams material, NumericsParams numerics,
               State initial, double h_min);

    void add_observer(StepObserver* o) { observers_.push_back(o); }
    // Cells (index j * nx + i) where material leaves the domain, e.g. outside a DEM's
    // data footprint: their content is removed after every step and counted as
    // outflow, so the mass balance still closes.
    void set_sink_cells(std::vector<std::uint8_t> mask) { sinks_ = std::move(mask); }
    // Called about every 0.1 s of wall time with the fraction of t_end done;
    // returning false interrupts the run (signals).
    void set_progress(std::function<bool(double)> p) { progress_ = std::move(p); }

    RunStatistics run();

    [[nodiscard]] const State& state() const { return state_; }
    [[nodiscard]] const Stepper& stepper() const { return stepper_; }
    [[nodiscard]] const Grid& grid() const { return grid_; }

private:
    [[nodiscard]] double kinetic_energy() const;
    [[nodiscard]] bool all_at_rest() const;
    void drain_sinks();

    Grid grid_;
    const TerrainFields& terrain_;
    MaterialParams material_;
    NumericsParams numerics_;
    State state_;
    Stepper stepper_;
    std::vector<StepObserver*> observers_;
    std::vector<std::uint8_t> sinks_;
    std::function<bool(double)> progress_;
};

// The automatic thin-layer depth: h_min_relative x the deepest initial cell
// (bed-normal), unless numerics.h_min is set.
double effective_h_min(const NumericsParams& n, const State& initial, const TerrainFields& terrain);

}  // namespace avalanche
