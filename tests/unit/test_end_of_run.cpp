// What a run reports about how it ended (RunStatistics, core/simulation.hpp): the
// kinetic energy of the state it ends with, and that energy as a fraction of its
// maximum, the ratio the stop rule compares with stop_ke_fraction (docs/numerics.md,
// "End of a run"). On the parametric chute (60 m, 45 deg to flat, cap of 2.5 m).
#include <gtest/gtest.h>

#include <cmath>

#include "avalanche/core/simulation.hpp"
#include "support/analytic_chute.hpp"

using namespace avalanche;
using namespace avalanche::analytic;

namespace {

struct EndedRun {
    RunStatistics stats;
    double kinetic_energy = 0.0;  // of the final state, summed here over every cell
};

EndedRun run_chute_to(double cell_size, double t_end) {
    NumericsParams n;
    n.t_end = t_end;
    const ChuteOutcome o = run_chute(n, cell_size, 60.0, 0.0);
    EndedRun r;
    r.stats = o.stats;
    // The definition, sum of h |u|^2 / 2 dA, evaluated directly: every cell, not only the
    // solver's active box, and without the scan's row sums.
    const State& s = o.final_state;
    long double sum = 0.0L;
    for (int j = 0; j < o.grid.ny; ++j)
        for (int i = 0; i < o.grid.nx; ++i) {
            const double h = s.h(i, j);
            if (h <= 0.0) continue;
            const long double u = s.hu(i, j) / static_cast<long double>(h);
            const long double v = s.hv(i, j) / static_cast<long double>(h);
            sum += 0.5L * h * (u * u + v * v);
        }
    r.kinetic_energy = static_cast<double>(sum * o.grid.dx * o.grid.dy);
    return r;
}

}  // namespace

TEST(EndOfRun, FinalKineticEnergyIsThatOfTheFinalState) {
    // At 2 s the cap is still accelerating down the 45 deg plane: far from stopping.
    const EndedRun r = run_chute_to(1.0, 2.0);
    ASSERT_EQ(r.stats.end_reason, EndReason::end_time);
    ASSERT_GT(r.kinetic_energy, 0.0);
    // Round-off of two summation orders (long double both) only.
    EXPECT_NEAR(r.stats.final_kinetic_energy, r.kinetic_energy, 1e-12 * r.kinetic_energy);
    EXPECT_NEAR(r.stats.final_kinetic_energy_fraction(),
                r.kinetic_energy / r.stats.max_kinetic_energy, 1e-12);
    // Still accelerating: the final energy is the largest so far, bar the last steps'
    // friction on the flat; far above the stop rule's 1e-4.
    EXPECT_GT(r.stats.final_kinetic_energy_fraction(), 0.5);
    EXPECT_LE(r.stats.final_kinetic_energy_fraction(), 1.0);
}

TEST(EndOfRun, ARunStoppedByTheEnergyRuleEndsBelowItsFraction) {
    // The cap comes to rest on the runout about 7 s after release; the rule stops the
    // run once the energy has stayed below 1e-4 of its maximum for 1 s.
    const EndedRun r = run_chute_to(0.5, 60.0);
    ASSERT_EQ(r.stats.end_reason, EndReason::stopped_kinetic_energy);
    EXPECT_LT(r.stats.simulated_time, 20.0);
    const NumericsParams defaults;
    EXPECT_GT(r.stats.final_kinetic_energy, 0.0);  // not at rest: that is the other rule
    EXPECT_LE(r.stats.final_kinetic_energy_fraction(), defaults.stop_ke_fraction);
    EXPECT_NEAR(r.stats.final_kinetic_energy, r.kinetic_energy, 1e-12 * r.kinetic_energy);
}

TEST(EndOfRun, NothingMovingGivesAZeroFraction) {
    RunStatistics st;
    EXPECT_EQ(st.final_kinetic_energy_fraction(), 0.0);
    st.max_kinetic_energy = 8.0;
    st.final_kinetic_energy = 2e-3;
    EXPECT_EQ(st.final_kinetic_energy_fraction(), 2e-3 / 8.0);
}
