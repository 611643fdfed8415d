// The stepper's energy cap (docs/numerics.md, "Energy cap"): no cell is faster than
// sqrt(2 (B - g z)), B the energy budget per unit mass of the state the run started
// from. Expected values are worked out by hand from that definition.
#include <gtest/gtest.h>

#include <cmath>

#include "avalanche/core/simulation.hpp"
#include "avalanche/numerics/stepper.hpp"
#include "extreme_scenes.hpp"
#include "support/analytic_harness.hpp"

using namespace avalanche;

namespace {

constexpr double kG = 9.81;

NumericsParams numerics_for_cap() {
    NumericsParams n;
    n.gravity = kG;
    return n;
}

MaterialParams isotropic() {
    MaterialParams m;
    m.earth_pressure = EarthPressureModel::isotropic;  // k = 1 in every direction
    return m;
}

}  // namespace

// One wet cell, h = 2 m moving at 3 m/s on a horizontal chute bed (z = 0, g_n = g),
// k = 1: B = 3^2/2 + g (0 + 2) + 2 * 1 * g * 2 = 4.5 + 6 g.
TEST(EnergyCap, BudgetIsKineticPlusFreeSurfacePlusPressureEnergy) {
    const Grid g = analytic::box_grid(0.0, 5.0, 0.0, 5.0, 1.0);
    const TerrainFields t = analytic::plane_terrain(g, 0.0, kG);
    State s(g);
    s.h(2, 2) = 2.0;
    s.hu(2, 2) = 2.0 * 3.0;
    const Stepper stepper(g, t, isotropic(), numerics_for_cap(), 1e-5);
    EXPECT_NEAR(stepper.energy_budget_of(s), 4.5 + 6.0 * kG, 1e-12);
    // Before the first step there is no cap.
    EXPECT_TRUE(std::isinf(stepper.energy_budget()));
}

// A uniform 1 m layer at 20 m/s on a frictionless horizontal bed, with the budget set to
// that of 10 m/s: one step leaves every cell at 10 m/s at most (the cap binds), most of
// them at exactly the cap, and the volume untouched (the cap acts on momentum only).
TEST(EnergyCap, BindsOnSpeedNotOnMass) {
    const Grid g = analytic::box_grid(0.0, 40.0, 0.0, 4.0, 1.0);
    const TerrainFields t = analytic::plane_terrain(g, 0.0, kG);
    State s = analytic::make_state(
        g, [](double, double, double, double) { return 1.0; },
        [](double, double) { return std::pair<double, double>{20.0, 0.0}; });
    MaterialParams m = isotropic();
    m.delta_deg = 0.0;
    NumericsParams n = numerics_for_cap();
    n.boundary = Boundary::wall;
    Stepper stepper(g, t, m, n, 1e-5);
    stepper.reset_active_box(s);
    stepper.set_energy_budget(0.5 * 10.0 * 10.0);
    const double v0 = total_volume(s, g);
    stepper.step(s, stepper.stable_dt(s));
    double fastest = 0.0;
    int at_cap = 0;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            ASSERT_GT(s.h(i, j), 0.0);
            const double speed = std::hypot(s.hu(i, j), s.hv(i, j)) / s.h(i, j);
            fastest = std::max(fastest, speed);
            if (std::abs(speed - 10.0) < 1e-9) ++at_cap;
        }
    EXPECT_LE(fastest, 10.0 * (1.0 + 1e-14));
    EXPECT_GT(at_cap, g.nx * g.ny / 2);
    EXPECT_NEAR(total_volume(s, g), v0, 1e-12 * v0);
}

// A 5 m layer at 30 m/s runs into a 100 m DEM wall (the regression scene cliff_up, k = 1):
// B = 30^2/2 + g (0 + 5) + 2 g 5 = 450 + 15 g, so the material can reach at most
// B / g = 60.9 m: nothing on top of the wall (z = 100 m) may move, whatever mass the
// DEM-frame fluxes carry there.
TEST(EnergyCap, NothingMovesAboveTheReachableHeight) {
    extremes::Case c;
    c.kind = extremes::Kind::cliff_up;
    c.h0 = 5.0;
    c.u0 = 30.0;
    c.earth_pressure = EarthPressureModel::isotropic;
    const extremes::Scene scene = extremes::make_scene(c);
    Simulation sim(scene.grid, scene.terrain, scene.material, scene.numerics, scene.initial,
                   effective_h_min(scene.numerics, scene.initial, scene.terrain));
    struct Watch : StepObserver {
        void on_step(const SimulationView& v) override {
            for (int j = 0; j < v.grid.ny; ++j)
                for (int i = 0; i < v.grid.nx; ++i) {
                    if (v.terrain.elevation(i, j) < 100.0 || v.state.h(i, j) <= 0.0) continue;
                    ++wet_on_top;
                    moving_on_top += v.state.hu(i, j) != 0.0 || v.state.hv(i, j) != 0.0;
                }
        }
        long wet_on_top = 0, moving_on_top = 0;
    } watch;
    sim.add_observer(&watch);
    sim.run();
    EXPECT_EQ(watch.moving_on_top, 0) << "of " << watch.wet_on_top << " wet cell-steps on the wall top";
}
