#include "avalanche/core/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "avalanche/core/error.hpp"

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

double RunStatistics::relative_mass_error() const {
    if (released_volume <= 0.0) return 0.0;
    return (final_volume + outflow_volume - released_volume) / released_volume;
}

double RunStatistics::cell_updates_per_second() const {
    return wall_seconds > 0.0 ? static_cast<double>(cell_updates) / wall_seconds : 0.0;
}

double total_volume(const State& s, const Grid& g) {
    long double sum = 0.0L;
    for (int j = 0; j < g.ny; ++j) {
        const double* h = s.h.row(j);
        for (int i = 0; i < g.nx; ++i) sum += h[i];
    }
    return static_cast<double>(sum * g.cell_area());
}

void check_state(const State& s, const Grid& g, const ActiveBox& box, double t) {
    int bad_i = -1, bad_j = -1;
    const char* what = nullptr;
    for (int j = box.j0; j < box.j1 && !what; ++j) {
        const double* h = s.h.row(j);
        const double* hu = s.hu.row(j);
        const double* hv = s.hv.row(j);
        for (int i = box.i0; i < box.i1; ++i) {
            if (!std::isfinite(h[i]) || !std::isfinite(hu[i]) || !std::isfinite(hv[i])) {
                what = "non-finite value (NaN or Inf) in the state";
            } else if (h[i] < 0.0) {
                what = "negative depth";
            }
            if (what) {
                bad_i = i;
                bad_j = j;
                break;
            }
        }
    }
    if (what) throw NumericalError(what, bad_i, bad_j, g.x_center(bad_i), g.y_center(bad_j), t);
}

double effective_h_min(const NumericsParams& n, const State& initial, const TerrainFields& terrain) {
    if (n.h_min > 0.0) return n.h_min;
    double deepest = 0.0;
    for (int j = 0; j < initial.h.ny(); ++j)
        for (int i = 0; i < initial.h.nx(); ++i)
            deepest = std::max(deepest, initial.h(i, j) * terrain.normal_thickness(i, j));
    return deepest > 0.0 ? n.h_min_relative * deepest : n.h_min_relative;
}

Simulation::Simulation(Grid grid, const TerrainFields& terrain, MaterialParams material,
                       NumericsParams numerics, State initial, double h_min)
    : grid_(grid),
      terrain_(terrain),
      material_(material),
      numerics_(numerics),
      state_(std::move(initial)),
      stepper_(grid_, terrain_, material_, numerics_, h_min) {
    stepper_.reset_active_box(state_);
}

double Simulation::kinetic_energy() const {
    const ActiveBox& b = stepper_.active_box();
    long double sum = 0.0L;
    for (int j = b.j0; j < b.j1; ++j) {
        for (int i = b.i0; i < b.i1; ++i) {
            const double h = state_.h(i, j);
            if (h <= 0.0) continue;
            sum += 0.5L * (state_.hu(i, j) * state_.hu(i, j) + state_.hv(i, j) * state_.hv(i, j)) / h;
        }
    }
    return static_cast<double>(sum * grid_.cell_area());
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

bool Simulation::all_at_rest() const {
    const ActiveBox& b = stepper_.active_box();
    for (int j = b.j0; j < b.j1; ++j)
        for (int i = b.i0; i < b.i1; ++i)
            if (state_.hu(i, j) != 0.0 || state_.hv(i, j) != 0.0) return false;
    return true;
}

RunStatistics Simulation::run() {
    RunStatistics st;
#ifdef _OPENMP
    st.threads = omp_get_max_threads();
#endif
    const auto wall0 = std::chrono::steady_clock::now();
    st.released_volume = total_volume(state_, grid_);
    double t = 0.0;
    std::uint64_t steps = 0;
    const auto view = [&]() { return SimulationView{grid_, terrain_, state_, t, steps, stepper_.active_box()}; };
    for (auto* o : observers_) o->on_start(view());
    for (auto* o : observers_) o->on_output(view());

    std::uint64_t outputs_done = 1;  // snapshot k is at t = k * output_interval
    double next_output = numerics_.output_interval;
    double last_output_t = 0.0;
    double ke_max = 0.0, quiet_since = -1.0;
    auto last_progress = wall0;
    EndReason reason = EndReason::end_time;
    const double t_end = numerics_.t_end;
    // Output times are k * interval; compare with a relative tolerance so that
    // accumulated round-off does not add a sliver step.
    const double eps_t = 1e-9 * std::max(1.0, t_end);

    while (t < t_end - eps_t) {
        double dt = stepper_.stable_dt(state_);
        if (!std::isfinite(dt)) {
            reason = stepper_.active_box().empty() ? EndReason::no_material : EndReason::stopped_at_rest;
            break;
        }
        const double target = std::min(next_output, t_end);
        bool hits_output = false;
        if (t + dt >= target - eps_t) {
            dt = target - t;
            hits_output = true;
        }
        stepper_.step(state_, dt);
        if (!sinks_.empty()) drain_sinks();
        ++steps;
        t = hits_output ? target : t + dt;
        check_state(state_, grid_, stepper_.active_box(), t);
        for (auto* o : observers_) o->on_step(view());
        if (hits_output && target == next_output && t < t_end - eps_t) {
            for (auto* o : observers_) o->on_output(view());
            last_output_t = t;
            ++outputs_done;
            next_output = numerics_.output_interval * static_cast<double>(outputs_done);
        }

        // End-of-run rule.
        const double ke = kinetic_energy();
        ke_max = std::max(ke_max, ke);
        if (all_at_rest()) {
            reason = EndReason::stopped_at_rest;
            break;
        }
        if (ke <= numerics_.stop_ke_fraction * ke_max) {
            if (quiet_since < 0.0) quiet_since = t;
            if (t - quiet_since >= numerics_.stop_duration) {
                reason = EndReason::stopped_kinetic_energy;
                break;
            }
        } else {
            quiet_since = -1.0;
        }

        if (progress_) {
            const auto now = std::chrono::steady_clock::now();
            if (now - last_progress > std::chrono::milliseconds(100)) {
                last_progress = now;
                if (!progress_(t / t_end)) {
                    reason = EndReason::interrupted;
                    break;
                }
            }
        }
    }
    if (progress_ && reason != EndReason::interrupted) progress_(1.0);
    if (t > last_output_t) for (auto* o : observers_) o->on_output(view());
    for (auto* o : observers_) o->on_end(view());

    st.end_reason = reason;
    st.simulated_time = t;
    st.steps = steps;
    st.cell_updates = stepper_.cell_updates();
    st.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    st.final_volume = total_volume(state_, grid_);
    st.outflow_volume = stepper_.outflow_volume();
    st.max_kinetic_energy = ke_max;
    return st;
}

}  // namespace avalanche
