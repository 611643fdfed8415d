// MODEL.md section 4, conservation: mass to round-off with wet/dry fronts on the
// parametric chute (smooth and rough bed, open edges with counted outflow, walls),
// positivity at every step, and exact mirror symmetry of a symmetric release.
//
// Norms: relative mass error (V_end + V_out - V_0) / V_0 from
// RunStatistics::relative_mass_error(), bound 1e-12 (MODEL.md 2.5: "below 1e-12 per
// run"); min h over every step >= 0 exactly; max |h(i, j) - h(i, ny-1-j)| == 0
// (the solver is built bitwise mirror-symmetric: -ffp-contract=off, paired sums).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "support/analytic_chute.hpp"
#include "support/analytic_harness.hpp"

using namespace avalanche;
using namespace avalanche::analytic;

namespace {
constexpr double kCell = 0.5;  // coarse cells keep each run ~0.5 s

ChuteOutcome run(Scheme s, Boundary b, double length, double relief, double t_end) {
    const ChuteOutcome o = run_chute(s, b, kCell, length, relief, t_end);
    std::cout << "[conservation] " << (s == Scheme::waf ? "WAF" : "Godunov") << ", "
              << (b == Boundary::open ? "open" : "wall") << ", length " << length << " m, relief "
              << relief << " m: t = " << o.stats.simulated_time << " s, " << o.steps
              << " steps, mass error " << o.stats.relative_mass_error() << ", outflow "
              << o.stats.outflow_volume << " of " << o.stats.released_volume << " m^3, min h "
              << o.min_h << ", asymmetry " << o.asymmetry << "\n";
    return o;
}

void expect_conservative(const ChuteOutcome& o) {
    EXPECT_LT(std::abs(o.stats.relative_mass_error()), 1e-12);
    EXPECT_GE(o.min_h, 0.0);
    EXPECT_EQ(o.asymmetry, 0.0);
}
}  // namespace

// Release, acceleration on 45 deg, the transition (curvature) and the runout, 8 s.
TEST(Conservation, SmoothChuteOpenEdges) {
    for (Scheme s : {Scheme::waf, Scheme::godunov}) {
        const ChuteOutcome o = run(s, Boundary::open, 60.0, 0.0, 8.0);
        expect_conservative(o);
        EXPECT_EQ(o.stats.outflow_volume, 0.0);  // nothing reaches an edge in 8 s
    }
}

// A 30 m plane without runout: most of the mass leaves through the lower edge; it
// must be counted, so V_end + V_out = V_0 to round-off.
TEST(Conservation, OutflowThroughOpenEdgeIsCounted) {
    for (Scheme s : {Scheme::waf, Scheme::godunov}) {
        const ChuteOutcome o = run(s, Boundary::open, 30.0, 0.0, 6.0);
        expect_conservative(o);
        EXPECT_GT(o.stats.outflow_volume, 0.5 * o.stats.released_volume);
    }
}

// Bumps of 0.3 m amplitude and 5 m wavelength: fronts split and rejoin around them.
TEST(Conservation, RoughChuteOpenAndWall) {
    for (Scheme s : {Scheme::waf, Scheme::godunov}) {
        for (Boundary b : {Boundary::open, Boundary::wall}) {
            const ChuteOutcome o = run(s, b, 60.0, 0.3, 8.0);
            expect_conservative(o);
            if (b == Boundary::wall) {
                EXPECT_EQ(o.stats.outflow_volume, 0.0);
            }
        }
    }
}
