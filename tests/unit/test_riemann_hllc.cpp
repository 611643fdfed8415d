// The HLLC kernel as a pure function (STYLE.md convention 1): consistency,
// mirror symmetry, wave ordering, dry-front speeds, and the WAF limits.
#include <gtest/gtest.h>

#include <cmath>

#include "avalanche/numerics/limiters.hpp"
#include "avalanche/numerics/riemann_hllc.hpp"

using namespace avalanche;

namespace {
constexpr double kG = 9.81;

void expect_flux_eq(const Conserved& a, const Conserved& b, double tol) {
    EXPECT_NEAR(a.h, b.h, tol);
    EXPECT_NEAR(a.qn, b.qn, tol);
    EXPECT_NEAR(a.qt, b.qt, tol);
}
}  // namespace

TEST(Hllc, ConsistentForEqualStates) {
    const double c = 0.8 * kG;
    for (double u : {-3.0, -0.5, 0.0, 0.7, 4.0}) {
        const Conserved q{1.3, 1.3 * u, 1.3 * 0.4};
        const Conserved f = hllc_flux(q, q, c, c, 1e-9);
        expect_flux_eq(f, physical_flux(1.3, u, 0.4, c), 1e-12);
    }
}

TEST(Hllc, StateAtRestGivesExactlyThePressureFlux) {
    const double c = 1.7 * kG;
    const Conserved q{2.0, 0.0, 0.0};
    const Conserved f = hllc_flux(q, q, c, c, 1e-9);
    EXPECT_EQ(f.h, 0.0);
    EXPECT_EQ(f.qn, 0.5 * c * 4.0);
    EXPECT_EQ(f.qt, 0.0);
}

TEST(Hllc, MirrorSymmetry) {
    // Reflecting the problem (x -> -x) reverses mass and tangential flux, keeps
    // the normal-momentum flux.
    const double cl = 0.9 * kG, cr = 1.2 * kG;
    const Conserved ql{1.5, 1.5 * 0.8, 1.5 * 0.3}, qr{0.6, 0.6 * -0.2, 0.6 * -0.1};
    const Conserved f = hllc_flux(ql, qr, cl, cr, 1e-9);
    const Conserved ml{qr.h, -qr.qn, qr.qt}, mr{ql.h, -ql.qn, ql.qt};
    const Conserved g = hllc_flux(ml, mr, cr, cl, 1e-9);
    EXPECT_NEAR(f.h, -g.h, 1e-12);
    EXPECT_NEAR(f.qn, g.qn, 1e-12);
    EXPECT_NEAR(f.qt, -g.qt, 1e-12);
}

TEST(Hllc, WaveSpeedsOrdered) {
    const double c = kG;
    for (double hl : {0.1, 1.0, 3.0})
        for (double hr : {0.2, 1.0, 5.0})
            for (double ul : {-2.0, 0.0, 3.0})
                for (double ur : {-1.0, 0.5}) {
                    const HllcFan fan = hllc_fan({hl, hl * ul, 0.0}, {hr, hr * ur, 0.0}, c, c, 1e-9);
                    EXPECT_LE(fan.s_l, fan.s_star);
                    EXPECT_LE(fan.s_star, fan.s_r);
                }
}

TEST(Hllc, DryFrontSpeedsAreRiemannInvariants) {
    const double c = 0.7 * kG, h = 2.0, u = 1.5;
    const double a = std::sqrt(c * h);
    const HllcFan right_dry = hllc_fan({h, h * u, 0.0}, {0.0, 0.0, 0.0}, c, c, 1e-6);
    EXPECT_DOUBLE_EQ(right_dry.s_l, u - a);
    EXPECT_DOUBLE_EQ(right_dry.s_star, u + 2.0 * a);
    EXPECT_DOUBLE_EQ(right_dry.s_r, u + 2.0 * a);
    const HllcFan left_dry = hllc_fan({0.0, 0.0, 0.0}, {h, h * u, 0.0}, c, c, 1e-6);
    EXPECT_DOUBLE_EQ(left_dry.s_l, u - 2.0 * a);
    EXPECT_DOUBLE_EQ(left_dry.s_star, u - 2.0 * a);
    EXPECT_DOUBLE_EQ(left_dry.s_r, u + a);
}

TEST(Hllc, DrySideNeverExportsMass) {
    // A state thinner than the dry tolerance is treated as dry: whatever its
    // momentum, no mass leaves it.
    const double c = kG;
    const Conserved thin{1e-7, 1e-7 * 50.0, 0.0}, wet{1.0, -0.5, 0.0};
    EXPECT_LE(hllc_flux(thin, wet, c, c, 1e-6).h, 0.0);
    const Conserved thin_l{1e-7, -1e-7 * 50.0, 0.0};
    EXPECT_GE(hllc_flux(wet, thin_l, c, c, 1e-6).h, -0.0);
}

TEST(Waf, ReducesToGodunovWithZeroLimiterAndToCentralAtUnitCourant) {
    const double c = kG;
    const Conserved ql{1.2, 0.3, 0.1}, qr{0.5, -0.4, 0.2};
    const HllcFan fan = hllc_fan(ql, qr, c, c, 1e-9);
    const double zero[3] = {0.0, 0.0, 0.0};
    expect_flux_eq(waf_flux(fan, 0.05, zero), hllc_flux(fan), 1e-12);
}

TEST(Limiters, TvdRegionAndSymmetry) {
    for (Limiter l : {Limiter::superbee, Limiter::van_leer, Limiter::van_albada, Limiter::minmod}) {
        EXPECT_EQ(limiter_psi(l, -1.0), 0.0);
        EXPECT_NEAR(limiter_psi(l, 1.0), 1.0, 1e-15);  // second order on smooth data
        for (double r : {0.1, 0.5, 2.0, 10.0}) {
            const double psi = limiter_psi(l, r);
            EXPECT_LE(psi, std::min(2.0 * r, 2.0) + 1e-15);
            EXPECT_GE(psi, 0.0);
            // psi(r)/r = psi(1/r) for the symmetric limiters
            EXPECT_NEAR(psi / r, limiter_psi(l, 1.0 / r), 1e-12);
        }
    }
}

// The WAF kernels take psi from the two jumps (limiter_psi_of_jumps): for every
// limiter it must be psi(jump_ratio(d_up, d_loc, tiny)) up to the round-off of the
// rearranged van Leer formula, with the flat and extremum cases exact.
TEST(Limiters, PsiOfJumpsIsPsiOfTheirRatio) {
    const double tiny = 1e-9;
    const double jumps[] = {-3.0, -0.7, -1e-3, -2e-9, -1e-12, 0.0, 1e-12, 5e-10, 1e-3, 0.25, 1.0, 40.0};
    for (Limiter l : {Limiter::superbee, Limiter::van_leer, Limiter::van_albada, Limiter::minmod}) {
        for (double up : jumps) {
            for (double loc : jumps) {
                const double ref = limiter_psi(l, jump_ratio(up, loc, tiny));
                const double psi = limiter_psi_of_jumps(l, up, loc, tiny);
                if (std::abs(loc) <= tiny || ref == 0.0) {
                    EXPECT_EQ(psi, ref) << "up " << up << " loc " << loc;  // flat or extremum: exact
                } else {
                    EXPECT_NEAR(psi, ref, 4e-16 * ref) << "up " << up << " loc " << loc;
                }
                EXPECT_GE(psi, 0.0);
                EXPECT_LE(psi, 2.0);
            }
        }
    }
    // Where r = d_up / d_loc overflows, 2r / (1 + r) is inf / inf; the jump form is not.
    EXPECT_NEAR(limiter_psi_of_jumps(Limiter::van_leer, 1e300, 1e-10, 1e-12), 2.0, 1e-15);
}
