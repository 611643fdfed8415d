#include "support/analytic_chute.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "avalanche/core/observer.hpp"
#include "avalanche/physics/release.hpp"
#include "support/analytic_harness.hpp"

namespace avalanche::analytic {

ChuteScene make_chute_scene(double cell_size, double length, double relief, double gravity) {
    ChuteScene c;
    c.geometry.slope_deg = 45.0;
    c.geometry.length = length;
    c.geometry.width = 40.0;
    if (length > 30.0) {
        c.geometry.transition_start = 25.0;
        c.geometry.transition_end = 30.0;
        c.geometry.runout_slope_deg = 0.0;
    }
    validate(c.geometry);
    c.grid = chute_grid(c.geometry, cell_size);
    c.terrain = chute_terrain(c.geometry, c.grid, gravity);
    if (relief > 0.0) {
        constexpr double kWave = 5.0;  // m, wavelength of the bumps
        const double w = 2.0 * std::numbers::pi / kWave;
        const Grid& g = c.grid;
        for (int j = 0; j < g.ny / 2; ++j) {
            const int jm = g.ny - 1 - j;  // mirror row about y = width / 2
            const double dy = g.y_center(j) - 0.5 * c.geometry.width;
            for (int i = 0; i < g.nx; ++i) {
                const double gc = gravity * std::cos(c.geometry.inclination(g.x_center(i)));
                const double x = g.x_center(i);
                const double dzdx = -relief * w * std::sin(w * x) * std::cos(w * dy);
                const double dzdy = -relief * w * std::cos(w * x) * std::sin(w * dy);
                c.terrain.ax(i, j) -= gc * dzdx;
                c.terrain.ax(i, jm) = c.terrain.ax(i, j);
                c.terrain.ay(i, j) = -gc * dzdy;
                c.terrain.ay(i, jm) = -c.terrain.ay(i, j);
            }
        }
        c.terrain.extend_to_ghosts();
    }
    const Field2D thickness = rasterize_release(CapRelease{{7.5, 20.0}, 2.5}, c.grid);
    c.initial = state_at_rest(c.grid, thickness, c.terrain);
    return c;
}

namespace {
class Watch : public StepObserver {
  public:
    void on_step(const SimulationView& v) override {
        min_h = std::min(min_h, min_depth(v.state, v.grid));
        asymmetry = std::max(asymmetry, mirror_asymmetry(v.state, v.grid));
    }
    double min_h = std::numeric_limits<double>::infinity();
    double asymmetry = 0.0;
};
}  // namespace

ChuteOutcome run_chute(NumericsParams n, double cell_size, double length, double relief) {
    const ScopedThreads serial(1);  // see analytic_harness.hpp
    const ChuteScene scene = make_chute_scene(cell_size, length, relief);
    n.output_interval = n.t_end;
    const MaterialParams material;  // Savage-Hutter, phi 35, delta 20 deg
    Simulation sim(scene.grid, scene.terrain, material, n, scene.initial,
                   effective_h_min(n, scene.initial, scene.terrain));
    Watch watch;
    sim.add_observer(&watch);
    ChuteOutcome o;
    o.stats = sim.run();
    o.min_h = watch.min_h;
    o.asymmetry = watch.asymmetry;
    o.steps = o.stats.steps;
    o.grid = scene.grid;
    o.final_state = sim.state();
    return o;
}

ChuteOutcome run_chute(Scheme scheme, Boundary boundary, double cell_size, double length,
                       double relief, double t_end) {
    NumericsParams n;
    n.scheme = scheme;
    n.boundary = boundary;
    n.t_end = t_end;
    return run_chute(n, cell_size, length, relief);
}

}  // namespace avalanche::analytic
