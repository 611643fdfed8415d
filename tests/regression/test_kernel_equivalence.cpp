// The first-order HLLC flux computes only the flux of the upwind region
// (riemann_hllc.hpp); it must be bitwise the flux hllc_flux(hllc_fan(...)) picks from
// the whole fan, which the WAF flux and the analytic tests use. Checked over wet/wet,
// wet/dry, dry/wet and dry/dry faces, sub- and supercritical, both flow directions.
#include <gtest/gtest.h>

#include <random>

#include "avalanche/numerics/riemann_hllc.hpp"
#include "support/same_bits.hpp"

using namespace avalanche;

namespace {

using test::same_bits;

}  // namespace

TEST(KernelEquivalence, UpwindHllcFluxIsBitwiseTheFansChoice) {
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> depth(0.0, 5.0), speed(-40.0, 40.0), coeff(0.1, 12.0);
    std::uniform_int_distribution<int> kind(0, 3);
    const double h_dry = 1e-3;
    long checked = 0, regions[4] = {0, 0, 0, 0};
    for (int n = 0; n < 200000; ++n) {
        const auto state = [&]() {
            Conserved q;
            switch (kind(rng)) {
                case 0: q.h = 0.0; break;            // empty
                case 1: q.h = 0.5 * h_dry; break;    // thinner than h_dry: dry
                default: q.h = depth(rng) + h_dry;   // wet
            }
            q.qn = q.h * speed(rng);
            q.qt = q.h * speed(rng);
            return q;
        };
        const Conserved ql = state(), qr = state();
        const double cl = coeff(rng), cr = coeff(rng);
        const HllcFan fan = hllc_fan(ql, qr, cl, cr, h_dry);
        const Conserved ref = hllc_flux(fan);
        const Conserved got = hllc_flux(ql, qr, cl, cr, h_dry);
        ASSERT_TRUE(same_bits(ref.h, got.h) && same_bits(ref.qn, got.qn) && same_bits(ref.qt, got.qt))
            << "face " << n << ": (" << ql.h << ", " << ql.qn << ", " << ql.qt << ") | (" << qr.h << ", "
            << qr.qn << ", " << qr.qt << "), c " << cl << " " << cr << ": fan (" << ref.h << ", " << ref.qn
            << ", " << ref.qt << ") upwind (" << got.h << ", " << got.qn << ", " << got.qt << ")";
        ++checked;
        ++regions[fan.s_l >= 0.0 ? 0 : fan.s_star >= 0.0 ? 1 : fan.s_r >= 0.0 ? 2 : 3];
    }
    // Every region of the fan was exercised, so the comparison covered each branch.
    for (long r : regions) EXPECT_GT(r, 1000);
    EXPECT_EQ(checked, 200000);
}
