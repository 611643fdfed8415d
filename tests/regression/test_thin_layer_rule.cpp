// The thin-layer rule (Wang & Li 2017 section 2.2.3; Stepper::thin_layer_velocities),
// checked on the state a step leaves (its last operation is the rule): a cell thinner
// than h_min with no neighbour at least h_min thick has no momentum; one with such a
// neighbour moves in the direction of its deepest such neighbour, at most as fast (the
// DEM frame keeps the neighbour's along-surface speed, and the cell's energy cap may
// lower it), and moves if the neighbour does, unless its energy cap stops it. A flow on
// a rough valley, on one thread and on two, after enough steps for fronts and films of
// both kinds.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <vector>

#include "avalanche/numerics/stepper.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"
#include "rough_valley.hpp"

using namespace avalanche;

namespace {

TEST(ThinLayerRule, ThinCellsStopOrMoveWithTheirDeepestWetNeighbour) {
    const Grid g{120, 200, 5.0, 5.0, 0.0, 0.0};
    const TerrainFields t = dem_terrain(g, avalanche::testing::rough_valley(g, 1.0, 0.001), 9.81);
    const double h_min = 1e-3;
    const int threads = omp_get_max_threads();
    for (int n : {1, 2}) {
        SCOPED_TRACE(n);
        omp_set_num_threads(n);
        const Field2D h0 = rasterize_release(ParaboloidRelease{{0.5 * g.x_max(), 0.25 * g.y_max()}, 60.0, 4.0}, g);
        State s = state_at_rest(g, h0, t);
        Stepper stepper(g, t, MaterialParams{}, NumericsParams{}, h_min);
        stepper.reset_active_box(s);
        for (int k = 0; k < 120; ++k) stepper.step(s, stepper.stable_dt(s));
        std::size_t stopped = 0, following = 0, bad = 0;
        for (int j = 1; j + 1 < g.ny; ++j)
            for (int i = 1; i + 1 < g.nx; ++i) {
                const double h = s.h(i, j);
                if (h >= h_min) continue;
                // The deepest neighbour at least h_min thick, the last of equals in the
                // order west, east, south, north (as the rule searches).
                const int ni[4] = {i - 1, i + 1, i, i}, nj[4] = {j, j, j - 1, j + 1};
                double best = h_min;
                int m = -1;
                for (int q = 0; q < 4; ++q)
                    if (s.h(ni[q], nj[q]) >= best) best = s.h(ni[q], nj[q]), m = q;
                if (m < 0) {
                    bad += s.hu(i, j) != 0.0 || s.hv(i, j) != 0.0;
                    stopped += h > 0.0;
                    continue;
                }
                if (h == 0.0) continue;  // nothing to move
                const double un = s.hu(ni[m], nj[m]) / best, vn = s.hv(ni[m], nj[m]) / best;
                const double u = s.hu(i, j) / h, v = s.hv(i, j) / h;
                const double speed_n = std::hypot(un, vn), speed = std::hypot(u, v);
                if (speed_n == 0.0) {
                    bad += speed != 0.0;
                    continue;
                }
                // Moving with a moving neighbour, unless its energy cap stops it. (The
                // update leaves such a cell zero momentum for the rule to set: a cell
                // the rule missed would stand still here.)
                const double cap2 =
                    2.0 * (stepper.energy_budget() - NumericsParams{}.gravity * t.elevation(i, j));
                if (speed == 0.0) {
                    bad += cap2 > 0.0;
                    continue;
                }
                // Parallel and in the same sense, a fraction in [0, 1] of the neighbour's.
                const double cross = u * vn - v * un, along = (u * un + v * vn) / (speed_n * speed_n);
                bad += std::abs(cross) > 1e-12 * speed_n * speed_n || along < 0.0 || along > 1.0 + 1e-12;
                following += speed > 0.0;
            }
        EXPECT_EQ(bad, 0u);
        // The check says something: thin cells of both kinds were there.
        EXPECT_GT(stopped, 50u);
        EXPECT_GT(following, 20u);
    }
    omp_set_num_threads(threads);
}

}  // namespace
