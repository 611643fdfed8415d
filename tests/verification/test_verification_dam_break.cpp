// MODEL.md section 4: the 1D granular dam break on an inclined plane with Coulomb
// friction against the exact solution of Mangeney, Heinrich & Roche (2000)
// (tests/support/analytic_dam_break.hpp), for both schemes.
//
// Norms: E1 = int |h - h_exact| dx / (h0 (x_f - x_r)) over the region where the
// infinite-reservoir solution holds (the mean depth error over the rarefaction, as a
// fraction of the reservoir depth); the front (last cell with h > 0.01 h0) and the
// rear (first cell with h < 0.99 h0) against the exact positions of those depths.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "support/analytic_harness.hpp"
#include "support/analytic_studies.hpp"

using namespace avalanche;
using namespace avalanche::analytic;

namespace {
constexpr double kDx = 0.1;  // 10 cells per reservoir depth; 1D, ~0.3 s per run


void report(const char* scheme_name, const DamBreakCase& c, const DamBreakResult& r) {
    std::cout << "[dam break] " << scheme_name << ", " << c.name << ", dx = " << r.dx
              << ": E1 = " << r.l1_relative << ", front " << r.front << " (exact " << r.front_exact
              << "), rear " << r.rear << " (exact " << r.rear_exact << "), mass " << r.mass_error
              << "\n";
}

struct Bounds {
    double e1;          // bound on E1
    double front_lag;   // bound on x_f,exact - x_f (m): the numerical front lags
    double rear_cells;  // bound on |x_r - x_r,exact| in cells
};

void check(Scheme s, const DamBreakCase& c, const Bounds& b) {
    const DamBreakResult r = run_dam_break(c, with_scheme(s), kDx);
    report(s == Scheme::waf ? "WAF" : "Godunov", c, r);
    EXPECT_LT(r.l1_relative, b.e1);
    EXPECT_LT(r.front_exact - r.front, b.front_lag);
    EXPECT_GT(r.front_exact - r.front, -2.0 * kDx);  // never ahead of the exact front
    EXPECT_LT(std::abs(r.rear - r.rear_exact), b.rear_cells * kDx);
    // Walls all round (the front never reaches x_hi): the volume is conserved to round-off.
    EXPECT_LT(std::abs(r.mass_error), 1e-13);
}
}  // namespace

// Measured at dx = 0.1 (docs/verification.md): WAF E1 = 4.6e-3, front lag 0.69 m, rear
// 1.7 cells; Godunov E1 = 7.7e-3, front lag 0.69 m, rear 6.7 cells. E1 bounds ~1.5x the
// measured values. The front lags by ~7 cells at the 1 % depth (the thin tip of a
// quadratically vanishing profile is smeared and slowed; the lag shrinks only at
// order ~0.6): bound 10 cells. The rear (a kink) is smeared over more cells by the
// first-order scheme: 3 cells for WAF, 12 for Godunov.
TEST(DamBreakMangeney, IsotropicWaf) {
    check(Scheme::waf, dam_break_isotropic(), {7e-3, 1.0, 3.0});
}
TEST(DamBreakMangeney, IsotropicGodunov) {
    check(Scheme::godunov, dam_break_isotropic(), {1.2e-2, 1.0, 12.0});
}

// Second case: theta = delta, m = 0. The reservoir must not move at all, and the
// rarefaction is Ritter's, with friction exactly balancing gravity inside it.
// Measured: WAF E1 = 4.3e-3, front lag 0.66 m, rear 2.1 cells; Godunov E1 = 9.9e-3,
// front lag 0.86 m, rear 10.1 cells.
TEST(DamBreakMangeney, BalancedFrictionWaf) {
    check(Scheme::waf, dam_break_balanced(), {7e-3, 1.0, 3.0});
}
TEST(DamBreakMangeney, BalancedFrictionGodunov) {
    check(Scheme::godunov, dam_break_balanced(), {1.5e-2, 1.2, 12.0});
}

// Savage-Hutter k: the exact solution has the active k throughout the fan. This failed
// (E1 0.09-0.2, growing under refinement) while a vanishing du/dx counted as passive:
// the reservoir at rest was passive. With du/dx = 0 counted as active it passes the
// same bounds as the isotropic case (measured WAF E1 3.9e-3 at dx = 0.1).
TEST(DamBreakMangeney, SavageHutterActiveK) {
    check(Scheme::waf, dam_break_savage_hutter(), {7e-3, 1.0, 3.0});
}
