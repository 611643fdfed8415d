#pragma once
// The checks of the extreme-case tests (test_extremes.cpp, test_random_extremes.cpp): a
// scene run through Simulation::run must stay free of NaN/Inf and negative depth,
// conserve mass to round-off with the outflow counted, and keep every speed below the
// scene's free-fall bound (extreme_scenes.hpp says why). Watch observes every step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <string>

#include "avalanche/core/error.hpp"
#include "avalanche/core/observer.hpp"
#include "avalanche/core/simulation.hpp"
#include "extreme_scenes.hpp"

namespace avalanche::extremes {

// Depth above which a cell shows in the hazard maps (the default h_thr, 1 cm): the
// fastest such cell is reported too, to tell a fixer whether the maps are affected.
constexpr double kMapDepth = 0.01;

// Watches every step: the fastest cell and the thinnest depth seen.
class Watch : public StepObserver {
  public:
    explicit Watch(const Scene& s) : scene_(s) {}
    void on_step(const SimulationView& v) override {
        ++steps;
        const ActiveBox& b = v.box;
        for (int j = b.j0; j < b.j1; ++j)
            for (int i = b.i0; i < b.i1; ++i) {
                min_h = std::min(min_h, v.state.h(i, j));
                const double speed = true_speed(scene_, v.state, i, j);
                if (v.state.h(i, j) * scene_.terrain.normal_thickness(i, j) >= kMapDepth)
                    max_speed_mapped = std::max(max_speed_mapped, speed);
                if (speed > max_speed) {
                    max_speed = speed;
                    where_i = i;
                    where_j = j;
                    when = v.t;
                    depth_there = v.state.h(i, j);
                }
            }
    }
    double min_h = std::numeric_limits<double>::infinity();
    double max_speed = 0.0, when = 0.0, depth_there = 0.0;
    double max_speed_mapped = 0.0;  // over cells at least kMapDepth thick
    int where_i = -1, where_j = -1;
    long steps = 0;

  private:
    const Scene& scene_;
};

// Runs the scene to its end and checks it (gtest failures), printing one line that
// starts with `label`. The run's statistics, or nothing when it threw.
inline std::optional<RunStatistics> run_and_check(const Scene& scene, const std::string& label) {
    EXPECT_NO_THROW(validate(scene.material));
    EXPECT_NO_THROW(validate(scene.numerics));
    const double h_min = effective_h_min(scene.numerics, scene.initial, scene.terrain);
    Simulation sim(scene.grid, scene.terrain, scene.material, scene.numerics, scene.initial, h_min);
    Watch watch(scene);
    sim.add_observer(&watch);
    RunStatistics st;
    try {
        st = sim.run();
    } catch (const NumericalError& e) {
        ADD_FAILURE() << label << ": NumericalError after " << watch.steps
                      << " steps: " << e.what();
        return std::nullopt;
    }
    const double bound = speed_bound(scene);
    ::testing::Test::RecordProperty("max_speed", std::to_string(watch.max_speed));
    std::cout << label << ": grid " << scene.grid.nx << "x" << scene.grid.ny << ", " << st.steps
              << " steps to t = " << st.simulated_time << " s (" << to_string(st.end_reason)
              << "), mass error " << st.relative_mass_error() << ", outflow " << st.outflow_volume
              << " of " << st.released_volume << " m^3, min h " << watch.min_h << ", max speed "
              << watch.max_speed << " m/s (bound " << bound << "; " << watch.max_speed_mapped
              << " m/s where h_n >= " << kMapDepth << " m)\n";
    EXPECT_GE(watch.min_h, 0.0);
    EXPECT_LT(std::abs(st.relative_mass_error()), 1e-12) << "outflow " << st.outflow_volume;
    // Every case, the cliffs and the frictionless outflow included: the solver's energy
    // cap (docs/numerics.md) keeps them below the bound, which is looser than the cap.
    EXPECT_LT(watch.max_speed, bound)
        << "at cell (" << watch.where_i << ", " << watch.where_j << "), t = " << watch.when
        << " s, h = " << watch.depth_there << " m (h_min " << h_min
        << " m); max where h_n >= " << kMapDepth << " m: " << watch.max_speed_mapped
        << " m/s; drop " << scene.drop << " m, u0 " << scene.u0 << " m/s, h0 " << scene.h0 << " m";
    EXPECT_GT(watch.steps, 0);
    return st;
}

}  // namespace avalanche::extremes
