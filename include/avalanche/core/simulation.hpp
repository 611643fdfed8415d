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
#include <limits>
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
    // The same sum for the state the run ends with: with final_kinetic_energy_fraction()
    // it says how near to the stop rule a run that ended by time was (docs/numerics.md,
    // "End of a run").
    double final_kinetic_energy = 0.0;
    [[nodiscard]] double relative_mass_error() const;
    // final_kinetic_energy / max_kinetic_energy; 0 when nothing ever moved.
    [[nodiscard]] double final_kinetic_energy_fraction() const;
    [[nodiscard]] double cell_updates_per_second() const;
};

// Volume held by the state (m^3), summed in long double so that the mass balance
// is judged on the solver's round-off, not the diagnostic's.
double total_volume(const State& s, const Grid& g);
// The same over the cells of `holding`, which holds every cell with material (the
// stepper's active box does): the same sum to the bit, since the cells outside add
// zeros, without reading them (a small flow on a large DEM: 4 M cells read twice a run).
double total_volume(const State& s, const Grid& g, const ActiveBox& holding);

// What the time loop needs from the state after each step.
struct StepScan {
    double kinetic_energy = 0.0;  // J/kg x m^3: sum of h |u|^2 / 2 dA over the box
    bool at_rest = true;          // every hu and hv in the box exactly zero
};

// One pass over the box after a step: throws NumericalError naming the first
// non-finite or negative cell in row-major order, else returns the kinetic energy and
// whether everything is at rest. Large boxes are scanned by all OpenMP threads; the
// result does not depend on their number (kinetic energy: one sum per row with a fixed
// grouping of its cells, state_scan_row; the rows added in order in long double).
StepScan scan_state(const State& s, const Grid& g, const ActiveBox& box, double t);

// Everything the time loop carries from one step to the next, besides the state and
// the observers: a run restored from it at a step boundary takes the same steps, bit
// for bit, as the run that saved it (dt is a function of the state alone).
struct LoopState {
    double t = 0.0;                   // simulated time (s)
    std::uint64_t steps = 0;
    std::uint64_t outputs_done = 1;   // snapshot k is at t = k * output_interval
    double next_output = 0.0;         // s
    double last_output_t = 0.0;       // s
    double ke_max = 0.0;              // running maximum of the kinetic energy
    double quiet_since = -1.0;        // s since when KE < stop_ke_fraction x ke_max; < 0: not quiet
    double released_volume = 0.0;     // m^3 at t = 0
    double outflow_volume = 0.0;      // m^3 through open edges and sinks so far
    std::uint64_t cell_updates = 0;   // so far
    double next_checkpoint = 0.0;     // s; 0 when checkpoints are off
    // The stepper's energy cap budget (Stepper::energy_budget), fixed by the first step;
    // +infinity before it.
    double energy_budget = std::numeric_limits<double>::infinity();
};

// A checkpoint as the loop hands it to its writer: the loop state, the state arrays
// (with ghost cells, exactly as the next step reads them) and every observer's data.
struct SimulationCheckpoint {
    LoopState loop;
    const State& state;
    CheckpointData observers;
};

// What a numerical fault leaves for diagnosis: the state after the last good step
// (with its loop state) and the state the failing step produced.
struct FaultReport {
    LoopState last_good_loop;
    const State& last_good;
    const State& failing;
    std::string what;  // the NumericalError message
};

class Simulation {
public:
    Simulation(Grid grid, const TerrainFields& terrain, MaterialParams material, NumericsParams numerics,
               State initial, double h_min);
    // The same where the caller knows a box that holds every cell of `initial` with
    // material (a prepared scene's release box): the first active box is searched in it
    // only, so a small release on a large DEM does not read the rest of the state.
    Simulation(Grid grid, const TerrainFields& terrain, MaterialParams material, NumericsParams numerics,
               State initial, double h_min, const ActiveBox& holding);

    void add_observer(StepObserver* o) { observers_.push_back(o); }
    // Cells (index j * nx + i) where material leaves the domain, e.g. outside a DEM's
    // data footprint: their content is removed after every step and counted as
    // outflow, so the mass balance still closes.
    void set_sink_cells(std::vector<std::uint8_t> mask) { sinks_ = std::move(mask); }
    // Called about every 0.1 s of wall time with the fraction of t_end done;
    // returning false interrupts the run (signals).
    void set_progress(std::function<bool(double)> p) { progress_ = std::move(p); }

    // Checkpoints every `interval` simulated seconds (0: only when interrupted), at a
    // step boundary; `write` must not change anything the run depends on.
    void set_checkpointing(double interval, std::function<void(const SimulationCheckpoint&)> write) {
        checkpoint_interval_ = interval;
        write_checkpoint_ = std::move(write);
    }
    // Continue from a checkpoint instead of t = 0: state arrays (with ghosts) as
    // saved, the loop state, and every attached observer's restore(). Call after
    // add_observer and before run(); on_start and the t = 0 output are skipped.
    void resume(const LoopState& loop, const std::vector<double>& h, const std::vector<double>& hu,
                const std::vector<double>& hv, const CheckpointData& observers);
    // Called with the last good and the failing state before a NumericalError
    // leaves run().
    void set_fault_handler(std::function<void(const FaultReport&)> f) { on_fault_ = std::move(f); }
    // Test hook: after step `step`, one wet cell becomes NaN, as a real fault would
    // (exercises the fault path end to end; 0 = off).
    void inject_fault_after_step(std::uint64_t step) { inject_fault_step_ = step; }

    RunStatistics run();

    [[nodiscard]] const State& state() const { return state_; }
    [[nodiscard]] const Stepper& stepper() const { return stepper_; }
    [[nodiscard]] const Grid& grid() const { return grid_; }

private:
    void drain_sinks();
    void remember_last_good();
    [[noreturn]] void report_fault(const LoopState& last_good, const std::string& what);

    Grid grid_;
    const TerrainFields& terrain_;
    MaterialParams material_;
    NumericsParams numerics_;
    State state_;
    Stepper stepper_;
    std::vector<StepObserver*> observers_;
    std::vector<std::uint8_t> sinks_;
    std::function<bool(double)> progress_;
    double checkpoint_interval_ = 0.0;
    std::function<void(const SimulationCheckpoint&)> write_checkpoint_;
    std::function<void(const FaultReport&)> on_fault_;
    std::uint64_t inject_fault_step_ = 0;
    bool resumed_ = false;
    LoopState loop_;  // initial loop state (t = 0, or the checkpoint's)
    // Cells [box) of the state before the current step, so that a fault can report
    // the last good state without copying the whole grid every step.
    ActiveBox saved_box_;
    std::vector<double> saved_h_, saved_hu_, saved_hv_;
};

// The automatic thin-layer depth: h_min_relative x the deepest initial cell
// (bed-normal), unless numerics.h_min is set.
double effective_h_min(const NumericsParams& n, const State& initial, const TerrainFields& terrain);
// The same, reading only the cells of `holding`, which holds every cell with material.
double effective_h_min(const NumericsParams& n, const State& initial, const TerrainFields& terrain,
                       const ActiveBox& holding);

}  // namespace avalanche
