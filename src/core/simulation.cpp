#include "avalanche/core/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "avalanche/core/error.hpp"
#include "avalanche/numerics/cell_rows.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace avalanche {

std::string to_string(EndReason r) {
    switch (r) {
        case EndReason::end_time: return "end_time";
        case EndReason::stopped_at_rest: return "stopped_at_rest";
        case EndReason::stopped_kinetic_energy: return "stopped_kinetic_energy";
        case EndReason::no_material: return "no_material";
        case EndReason::interrupted: return "interrupted";
    }
    return "unknown";
}

const std::vector<double>& CheckpointData::real(const std::string& name, long long expected_size) const {
    const auto it = reals.find(name);
    if (it == reals.end() || (expected_size >= 0 && it->second.size() != static_cast<std::size_t>(expected_size)))
        throw InputError("checkpoint", "dataset " + name + " is missing or does not fit this run");
    return it->second;
}

const std::vector<std::int64_t>& CheckpointData::integer(const std::string& name, long long expected_size) const {
    const auto it = integers.find(name);
    if (it == integers.end() ||
        (expected_size >= 0 && it->second.size() != static_cast<std::size_t>(expected_size)))
        throw InputError("checkpoint", "dataset " + name + " is missing or does not fit this run");
    return it->second;
}

double RunStatistics::relative_mass_error() const {
    if (released_volume <= 0.0) return 0.0;
    return (final_volume + outflow_volume - released_volume) / released_volume;
}

double RunStatistics::final_kinetic_energy_fraction() const {
    return max_kinetic_energy > 0.0 ? final_kinetic_energy / max_kinetic_energy : 0.0;
}

double RunStatistics::cell_updates_per_second() const {
    return wall_seconds > 0.0 ? static_cast<double>(cell_updates) / wall_seconds : 0.0;
}

double total_volume(const State& s, const Grid& g) { return total_volume(s, g, ActiveBox{0, g.nx, 0, g.ny}); }

double total_volume(const State& s, const Grid& g, const ActiveBox& holding) {
    long double sum = 0.0L;
    const ActiveBox b = holding.clipped(g.nx, g.ny);
    for (int j = b.j0; j < b.j1; ++j) {
        const double* h = s.h.row(j);
        for (int i = b.i0; i < b.i1; ++i) sum += h[i];
    }
    return static_cast<double>(sum * g.cell_area());
}

namespace {

// The checkpoint's copy of the cells' Savage-Hutter regimes (Stepper::regime).
constexpr const char* kRegimeDataset = "solver/regime";
// ... and of the cells held at rest by friction (numerics.rest_faces; Stepper::held_at_rest):
// empty before the first advection.
constexpr const char* kHeldDataset = "solver/held_at_rest";

// Boxes smaller than this are scanned or copied on one thread (stepper.hpp: waking
// the team costs more than a pass over a few thousand cells).
constexpr std::size_t kMinCellsPerThreadedPass = Stepper::kMinCellsPerThreadedStep;

[[noreturn]] void throw_bad_cell(const State& s, const Grid& g, int i, int j, double t) {
    const bool finite =
        std::isfinite(s.h(i, j)) && std::isfinite(s.hu(i, j)) && std::isfinite(s.hv(i, j));
    throw NumericalError(finite ? "negative depth" : "non-finite value (NaN or Inf) in the state",
                         i, j, g.x_center(i), g.y_center(j), t);
}

}  // namespace

// One fused pass instead of three serial scans (state check, kinetic energy, rest
// test): on a large box these were the serial part of every step that limited the
// scaling to two threads. Each row is scanned on its own and the rows are combined in
// row order, so the first bad cell is the row-major first and the sum is independent
// of the thread count. (Before, one long double accumulator ran over all cells. The
// per-row sums differ from it in the last bits: in ~1 % of the steps of the chute and
// valley benchmarks by one ulp of the double, on a wet 1000 x 1000 plane by ~1e-14
// relative in every step, the round-off of the single accumulator against a binary128
// sum; the per-row sum's error there is ~1e-17. Step counts and end reasons were
// unchanged.) Each row is summed in double by a vector kernel with a fixed grouping
// (state_scan_row, cell_rows.hpp), the rows in long double.
StepScan scan_state(const State& s, const Grid& g, const ActiveBox& box, double t) {
    StepScan out;
    if (box.empty()) return out;
    std::vector<StateRowScan> rows(static_cast<std::size_t>(box.j1 - box.j0));
    const bool threaded = box.cells() >= kMinCellsPerThreadedPass;
#pragma omp parallel for schedule(static) if (threaded)
    for (int j = box.j0; j < box.j1; ++j)
        rows[static_cast<std::size_t>(j - box.j0)] =
            state_scan_row(s.h.row(j), s.hu.row(j), s.hv.row(j), box.i0, box.i1);
    long double kinetic = 0.0L;
    for (int j = box.j0; j < box.j1; ++j) {
        const StateRowScan& r = rows[static_cast<std::size_t>(j - box.j0)];
        if (r.first_bad >= 0) throw_bad_cell(s, g, r.first_bad, j, t);
        kinetic += r.twice_kinetic;
        if (r.moving) out.at_rest = false;
    }
    out.kinetic_energy = static_cast<double>(0.5L * kinetic * g.cell_area());
    return out;
}

double effective_h_min(const NumericsParams& n, const State& initial, const TerrainFields& terrain) {
    return effective_h_min(n, initial, terrain, ActiveBox{0, initial.h.nx(), 0, initial.h.ny()});
}

double effective_h_min(const NumericsParams& n, const State& initial, const TerrainFields& terrain,
                       const ActiveBox& holding) {
    if (n.h_min > 0.0) return n.h_min;
    double deepest = 0.0;
    // The terrain of released cells only: elsewhere h = 0, and reading a terrain made on
    // demand (terrain.hpp) there would touch memory no run needs. Made here, not left to
    // whoever built the state: a state set cell by cell, not by state_at_rest, found
    // the normal thicknesses of tiles not yet made at zero, and h_min_relative alone.
    // Only the box of the released cells is made, not all of `holding` (the whole grid
    // for the overload without it).
    const ActiveBox b = holding.clipped(initial.h.nx(), initial.h.ny());
    ActiveBox released;
    for (int j = b.j0; j < b.j1; ++j)
        for (int i = b.i0; i < b.i1; ++i)
            if (initial.h(i, j) > 0.0) released = released.united(ActiveBox{i, i + 1, j, j + 1});
    if (released.empty()) return n.h_min_relative;
    terrain.ensure(released.i0, released.i1, released.j0, released.j1);
    for (int j = released.j0; j < released.j1; ++j)
        for (int i = released.i0; i < released.i1; ++i)
            if (initial.h(i, j) > 0.0)
                deepest = std::max(deepest, initial.h(i, j) * terrain.normal_thickness(i, j));
    return deepest > 0.0 ? n.h_min_relative * deepest : n.h_min_relative;
}

Simulation::Simulation(Grid grid, const TerrainFields& terrain, MaterialParams material,
                       NumericsParams numerics, State initial, double h_min)
    : Simulation(grid, terrain, material, numerics, std::move(initial), h_min, ActiveBox{0, grid.nx, 0, grid.ny}) {}

Simulation::Simulation(Grid grid, const TerrainFields& terrain, MaterialParams material,
                       NumericsParams numerics, State initial, double h_min, const ActiveBox& holding)
    : grid_(grid),
      terrain_(terrain),
      material_(material),
      numerics_(numerics),
      state_(std::move(initial)),
      stepper_(grid_, terrain_, material_, numerics_, h_min) {
    stepper_.reset_active_box(state_, holding);
}

void Simulation::drain_sinks() {
    const ActiveBox& b = stepper_.active_box();
    long double drained = 0.0L;
    for (int j = b.j0; j < b.j1; ++j)
        for (int i = b.i0; i < b.i1; ++i) {
            if (!sinks_[static_cast<std::size_t>(j) * grid_.nx + i] || state_.h(i, j) == 0.0) continue;
            drained += state_.h(i, j);
            state_.h(i, j) = state_.hu(i, j) = state_.hv(i, j) = 0.0;
        }
    if (drained > 0.0L)
        stepper_.set_outflow_volume(stepper_.outflow_volume() + static_cast<double>(drained * grid_.cell_area()));
}

void Simulation::resume(const LoopState& loop, const std::vector<double>& h, const std::vector<double>& hu,
                        const std::vector<double>& hv, const CheckpointData& observers) {
    // The checkpoint's arrays hold the cells without the rows' padding (Field2D::packed).
    const std::size_t n = state_.h.packed_size();
    if (h.size() != n || hu.size() != n || hv.size() != n)
        throw InputError("checkpoint", "the state arrays do not fit the grid of the run");
    state_.h.set_packed(h);
    state_.hu.set_packed(hu);
    state_.hv.set_packed(hv);
    // The box is recomputed from the state: the steps that follow find the same wet
    // cells from it as from the box the saving run carried (both hold every wet cell),
    // so dt and every update are unchanged (tests/cli/test_checkpoint_resume.cpp).
    stepper_.reset_active_box(state_);
    stepper_.set_outflow_volume(loop.outflow_volume);
    if (std::isfinite(loop.energy_budget)) stepper_.set_energy_budget(loop.energy_budget);
    const std::vector<std::int64_t>& regime =
        observers.integer(kRegimeDataset, static_cast<long long>(n));
    for (const std::int64_t r : regime)
        if (r < 0 || r > kRegimeAtStart)
            throw InputError("checkpoint", "dataset " + std::string(kRegimeDataset) +
                                               " holds " + std::to_string(r) +
                                               ", expected regime flags 0 to 3");
    CellVector<RegimeFlags> regime_cells(state_.h.raw().size(), kRegimeAtStart);
    state_.h.unpack(regime.data(), regime_cells.data());
    stepper_.set_regime(std::move(regime_cells));
    if (numerics_.rest_faces) {
        const std::vector<std::int64_t>& held =
            observers.integer(kHeldDataset, static_cast<long long>(n));
        for (const std::int64_t f : held)
            if (f != 0 && f != 1)
                throw InputError("checkpoint", "dataset " + std::string(kHeldDataset) + " holds " +
                                                   std::to_string(f) + ", expected 0 or 1");
        // Before the first step the first advection makes its flags from the state.
        if (loop.steps > 0) {
            CellVector<HeldFlag> held_cells(state_.h.raw().size(), 0);
            state_.h.unpack(held.data(), held_cells.data());
            stepper_.set_held_at_rest(std::move(held_cells));
        }
    }
    for (auto* o : observers_) o->restore(observers);
    loop_ = loop;
    resumed_ = true;
}

void Simulation::remember_last_good() {
    // The next step updates at most the current box widened by the growth of the wet
    // area in one step (stepper.cpp searches 3 cells beyond it).
    const ActiveBox b = stepper_.active_box();
    saved_box_ = b.empty() ? ActiveBox{0, grid_.nx, 0, grid_.ny} : b.widened(3, grid_.nx, grid_.ny);
    const std::size_t w = static_cast<std::size_t>(saved_box_.i1 - saved_box_.i0);
    const std::size_t n = saved_box_.cells();
    saved_h_.resize(n);
    saved_hu_.resize(n);
    saved_hv_.resize(n);
    // Every step of a run with a fault handler (the CLI's) copies the box: on a large
    // box a serial copy would be a serial part of the step.
#pragma omp parallel for schedule(static) if (n >= kMinCellsPerThreadedPass)
    for (int j = saved_box_.j0; j < saved_box_.j1; ++j) {
        const std::size_t o = static_cast<std::size_t>(j - saved_box_.j0) * w;
        std::copy_n(state_.h.row(j) + saved_box_.i0, w, saved_h_.begin() + static_cast<std::ptrdiff_t>(o));
        std::copy_n(state_.hu.row(j) + saved_box_.i0, w, saved_hu_.begin() + static_cast<std::ptrdiff_t>(o));
        std::copy_n(state_.hv.row(j) + saved_box_.i0, w, saved_hv_.begin() + static_cast<std::ptrdiff_t>(o));
    }
}

void Simulation::report_fault(const LoopState& last_good_loop, const std::string& what) {
    State last_good = state_;
    const std::size_t w = static_cast<std::size_t>(saved_box_.i1 - saved_box_.i0);
    for (int j = saved_box_.j0; j < saved_box_.j1; ++j) {
        const auto o = static_cast<std::ptrdiff_t>(static_cast<std::size_t>(j - saved_box_.j0) * w);
        std::copy_n(saved_h_.begin() + o, w, last_good.h.row(j) + saved_box_.i0);
        std::copy_n(saved_hu_.begin() + o, w, last_good.hu.row(j) + saved_box_.i0);
        std::copy_n(saved_hv_.begin() + o, w, last_good.hv.row(j) + saved_box_.i0);
    }
    on_fault_(FaultReport{last_good_loop, last_good, state_, what});
    throw;  // only called from a catch block: the NumericalError goes on to run_cli
}

RunStatistics Simulation::run() {
    RunStatistics st;
#ifdef _OPENMP
    st.threads = omp_get_max_threads();
#endif
    const auto wall0 = std::chrono::steady_clock::now();
    LoopState L = loop_;
    if (!resumed_) {
        L = LoopState{};
        L.released_volume = total_volume(state_, grid_, stepper_.active_box());
        L.next_output = numerics_.output_interval;
        L.next_checkpoint = checkpoint_interval_;
    }
    const std::uint64_t cell_updates_before = L.cell_updates;  // the stepper counts from 0 again
    double& t = L.t;
    std::uint64_t& steps = L.steps;
    const auto view = [&]() {
        return SimulationView{grid_, terrain_, state_, t, steps, stepper_.active_box(),
                              steps > 0 ? stepper_.bands() : std::span<const ActiveBox>{}};
    };
    if (!resumed_) {
        for (auto* o : observers_) o->on_start(view());
        for (auto* o : observers_) o->on_output(view());
    }
    const auto checkpoint = [&]() {
        if (!write_checkpoint_) return;
        L.outflow_volume = stepper_.outflow_volume();
        L.cell_updates = cell_updates_before + stepper_.cell_updates();
        L.energy_budget = stepper_.energy_budget();
        SimulationCheckpoint c{L, state_, {}};
        for (auto* o : observers_) o->save(c.observers);
        // The solver's own carried state besides the fields: the cells' regimes.
        const CellVector<RegimeFlags> regime = stepper_.regime();
        std::vector<std::int64_t>& saved = c.observers.integers[kRegimeDataset];
        if (regime.empty())  // no advection yet: every cell starts active
            saved.assign(state_.h.packed_size(), kRegimeAtStart);
        else
            saved = state_.h.packed<std::int64_t>(regime.data());
        if (numerics_.rest_faces) {
            // Empty before the first advection, and with S L S (which reads only the
            // friction stage's flags): saved as zeros, which the next step never reads.
            const CellVector<HeldFlag> held = stepper_.held_at_rest();
            std::vector<std::int64_t>& saved_held = c.observers.integers[kHeldDataset];
            if (held.empty())
                saved_held.assign(state_.h.packed_size(), 0);
            else
                saved_held = state_.h.packed<std::int64_t>(held.data());
        }
        write_checkpoint_(c);
    };

    auto last_progress = wall0;
    EndReason reason = EndReason::end_time;
    const double t_end = numerics_.t_end;
    // Output times are k * interval; compare with a relative tolerance so that
    // accumulated round-off does not add a sliver step.
    const double eps_t = 1e-9 * std::max(1.0, t_end);

    // The stable step the last step computed of the state it left (stable_dt_of_last_step),
    // kept only while nothing else has changed that state.
    std::optional<double> next_dt;
    while (t < t_end - eps_t) {
        double dt = next_dt ? *next_dt : stepper_.stable_dt(state_);
        if (!std::isfinite(dt)) {
            reason = stepper_.active_box().empty() ? EndReason::no_material : EndReason::stopped_at_rest;
            break;
        }
        const double target = std::min(L.next_output, t_end);
        bool hits_output = false;
        if (t + dt >= target - eps_t) {
            dt = target - t;
            hits_output = true;
        }
        LoopState before = L;  // the last good step, for a fault report
        if (on_fault_) {
            before.outflow_volume = stepper_.outflow_volume();
            before.cell_updates = cell_updates_before + stepper_.cell_updates();
            before.energy_budget = stepper_.energy_budget();
            remember_last_good();
        }
        stepper_.step(state_, dt);
        next_dt = stepper_.stable_dt_of_last_step();
        if (!sinks_.empty()) {
            drain_sinks();
            next_dt.reset();
        }
        ++steps;
        t = hits_output ? target : t + dt;
        if (inject_fault_step_ != 0 && steps == inject_fault_step_ && !stepper_.active_box().empty()) {
            next_dt.reset();
            const ActiveBox& b = stepper_.active_box();
            state_.h((b.i0 + b.i1) / 2, (b.j0 + b.j1) / 2) = std::numeric_limits<double>::quiet_NaN();
        }
        StepScan scan;
        try {
            scan = scan_state(state_, grid_, stepper_.active_box(), t);
        } catch (const NumericalError& e) {
            if (on_fault_) report_fault(before, e.what());
            throw;
        }
        for (auto* o : observers_) o->on_step(view());
        if (hits_output && target == L.next_output && t < t_end - eps_t) {
            for (auto* o : observers_) o->on_output(view());
            L.last_output_t = t;
            ++L.outputs_done;
            L.next_output = numerics_.output_interval * static_cast<double>(L.outputs_done);
        }

        // End-of-run rule.
        // (The observers above only read the state: the scan still describes it.)
        const double ke = scan.kinetic_energy;
        L.ke_max = std::max(L.ke_max, ke);
        if (scan.at_rest) {
            reason = EndReason::stopped_at_rest;
            break;
        }
        if (ke <= numerics_.stop_ke_fraction * L.ke_max) {
            if (L.quiet_since < 0.0) L.quiet_since = t;
            if (t - L.quiet_since >= numerics_.stop_duration) {
                reason = EndReason::stopped_kinetic_energy;
                break;
            }
        } else {
            L.quiet_since = -1.0;
        }

        // The step is complete here: a checkpoint taken now restarts at the top of the
        // loop with nothing left over.
        bool checkpointed = false;
        if (checkpoint_interval_ > 0.0 && t >= L.next_checkpoint - eps_t) {
            // The schedule is k x interval, counted from the time reached, so a long
            // step never queues several checkpoints.
            L.next_checkpoint =
                checkpoint_interval_ * (std::floor(t / checkpoint_interval_ + 1e-9) + 1.0);
            checkpoint();
            checkpointed = true;
        }

        if (progress_) {
            const auto now = std::chrono::steady_clock::now();
            if (now - last_progress > std::chrono::milliseconds(100)) {
                last_progress = now;
                if (!progress_(t / t_end)) {
                    reason = EndReason::interrupted;
                    if (!checkpointed) checkpoint();
                    break;
                }
            }
        }
    }
    if (progress_ && reason != EndReason::interrupted) progress_(1.0);
    if (t > L.last_output_t) for (auto* o : observers_) o->on_output(view());
    for (auto* o : observers_) o->on_end(view());

    st.end_reason = reason;
    st.simulated_time = t;
    st.steps = steps;
    st.cell_updates = cell_updates_before + stepper_.cell_updates();
    st.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    st.released_volume = L.released_volume;
    st.final_volume = total_volume(state_, grid_, stepper_.active_box());
    st.outflow_volume = stepper_.outflow_volume();
    st.max_kinetic_energy = L.ke_max;
    // Scanned again rather than kept from the loop: a run that took no step (resumed at
    // its end, interrupted at once) has no scan of its own.
    st.final_kinetic_energy = scan_state(state_, grid_, stepper_.active_box(), t).kinetic_energy;
    return st;
}

}  // namespace avalanche
