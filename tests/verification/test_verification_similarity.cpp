// MODEL.md section 4: the Savage-Hutter similarity solution (Savage & Hutter 1991;
// Hutter et al. 1993), a parabolic cap (1D) or paraboloid (2D) sliding down a plane
// while it spreads (tests/support/analytic_similarity.hpp, derived there).
//
// Norms: E1 = int |h - h_exact| dA / V (relative L1 depth error); the centroid x_c
// from the first moment; the half-lengths L_x, L_y from the second moments
// (L^2 = 5 var in 1D, 6 var in 2D for these shapes); the mean velocity
// (momentum / volume), which for this solution is exactly x_c'.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "support/analytic_similarity.hpp"
#include "support/analytic_harness.hpp"
#include "support/analytic_studies.hpp"

using namespace avalanche;
using namespace avalanche::analytic;

namespace {

struct Bounds {
    double e1;      // bound on E1
    double x_c;     // bound on |x_c - exact| (m)
    double spread;  // bound on |L - L_exact| / L_exact
};

SimilarityResult check(Scheme s, const SimilarityCase& c, double dx, const Bounds& b) {
    const SimilarityResult r = run_similarity(c, with_scheme(s), dx);
    std::cout << "[similarity] " << (s == Scheme::waf ? "WAF" : "Godunov") << ", " << c.name
              << ", dx = " << dx << ": E1 = " << r.l1_relative << ", x_c " << r.x_c << " (exact "
              << r.x_c_exact << "), L_x " << r.l_x << " (" << r.l_x_exact << "), L_y " << r.l_y
              << " (" << r.l_y_exact << "), mean u " << r.mean_u << " (" << r.mean_u_exact << ")\n";
    EXPECT_LT(r.l1_relative, b.e1);
    EXPECT_LT(std::abs(r.x_c - r.x_c_exact), b.x_c);
    EXPECT_LT(std::abs(r.l_x - r.l_x_exact) / r.l_x_exact, b.spread);
    if (c.exact.two_d) {
        EXPECT_LT(std::abs(r.l_y - r.l_y_exact) / r.l_y_exact, b.spread);
    }
    return r;
}
}  // namespace

TEST(SimilaritySolution, RungeKuttaIsConvergedTo1e10) {
    // The exact solution is an ODE integral: halving the RK4 step must not move it.
    for (const SimilarityCase& c : {similarity_1d(EarthPressureModel::savage_hutter),
                                    similarity_2d(EarthPressureModel::isotropic)}) {
        const SimilarityState a = similarity_at(c.exact, c.t_end),
                              b = similarity_at(c.exact, c.t_end, 5e-5);
        EXPECT_LT(std::abs(a.l_x - b.l_x), 1e-10);
        EXPECT_LT(std::abs(a.l_y - b.l_y), 1e-10);
        EXPECT_LT(std::abs(a.x_c - b.x_c), 1e-10);
    }
}

// 1D, dx = 0.1 m (40 cells over the initial cap). Measured (docs/verification.md):
// WAF E1 = 9.9e-3 (iso) / 1.1e-2 (SH), L_x within 0.05 %; Godunov E1 = 2.4e-2 / 3.2e-2,
// L_x 2 % / 3 % too wide (numerical diffusion at the edges). Both converge at first
// order (the depth has a kink at the dry edges). The centroid moves with the exact
// rigid-block law to < 2e-3 m. Bounds: ~1.5x the measured values.
TEST(SimilaritySolution, OneDimensionalWaf) {
    for (EarthPressureModel m : {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter})
        check(Scheme::waf, similarity_1d(m), 0.1, {1.8e-2, 4e-3, 2e-3});
}
TEST(SimilaritySolution, OneDimensionalGodunov) {
    for (EarthPressureModel m : {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter})
        check(Scheme::godunov, similarity_1d(m), 0.1, {5e-2, 4e-3, 5e-2});
}

TEST(SimilaritySolution, OneDimensionalConvergesAtFirstOrder) {
    // The dry edge (h ~ distance) limits both schemes to first order in L1: assert
    // an observed order >= 0.8 between dx = 0.2 and 0.1 (measured 0.92-0.97).
    for (Scheme s : {Scheme::waf, Scheme::godunov}) {
        const SimilarityCase c = similarity_1d(EarthPressureModel::savage_hutter);
        const double e0 = run_similarity(c, with_scheme(s), 0.2).l1_relative;
        const double e1 = run_similarity(c, with_scheme(s), 0.1).l1_relative;
        EXPECT_GT(std::log2(e0 / e1), 0.8);
    }
}

// 2D, delta = 0, dx = 0.25 m (12 cells per initial half-width). Measured: WAF E1 =
// 3.3e-2 (iso) / 3.7e-2 (SH), L_x, L_y within 0.35 %, x_c within 4e-3 m; Godunov E1 =
// 0.11 / 0.13, L_x 7 % / 10.5 % too wide. Bounds ~1.5x.
// The spread L (from the second moment) is sensitive to the first-order wet/dry fronts:
// with the wave-strength limiter the interior is less diffused and the spread error at
// dx = 0.25 is 1.3 % (isotropic) and 1.8 % (SH), converging at second order
// (4.4 %, 1.3 %, 0.29 % iso and 5.2 %, 1.8 %, 0.45 % SH at dx = 0.5, 0.25, 0.125).
// Bounds: 2.5 % at dx = 0.25, and halving dx must divide the error by at least 2.5.
TEST(SimilaritySolution, TwoDimensionalWaf) {
    for (EarthPressureModel m : {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter}) {
        const SimilarityResult coarse = check(Scheme::waf, similarity_2d(m), 0.25, {6e-2, 1e-2, 2.5e-2});
        const SimilarityResult fine = check(Scheme::waf, similarity_2d(m), 0.125, {2e-2, 1e-2, 1e-2});
        EXPECT_GT(std::abs(coarse.l_x - coarse.l_x_exact), 2.5 * std::abs(fine.l_x - fine.l_x_exact));
        EXPECT_GT(coarse.l1_relative, 2.0 * fine.l1_relative);
    }
}
TEST(SimilaritySolution, TwoDimensionalGodunov) {
    for (EarthPressureModel m : {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter})
        check(Scheme::godunov, similarity_2d(m), 0.25, {0.2, 1e-2, 0.16});
}

// Released from rest: du/dx = 0 at t = 0 and tiny early on (L'/L = 0.03 1/s at 0.1 s),
// so the velocity noise of the scheme decides the regime. With the regime taken from the
// central difference of u a pattern of passive cells (k_pass / k_act = 6.6) grew, the
// cap spread too fast and the error GREW under refinement (WAF E1 = 6e-2, 1.4e-1,
// 2.6e-1 at dx = 0.2, 0.1, 0.05; L_x 6.2, 6.6, 7.2 m against 5.82). With the central
// difference confirmed at a second scale (regime_rows.cpp, next_regime) it converges: measured
// E1 = 6.4e-3, 2.0e-3, 7.0e-4, L_x within 0.08 % at dx = 0.1 (docs/verification.md,
// finding 2). Bounds: those of the cap released spreading; order >= 1.2 from dx = 0.1 to
// 0.05 (measured 1.54).
TEST(SimilaritySolution, SavageHutterFromRest) {
    const SimilarityCase c = similarity_1d(EarthPressureModel::savage_hutter, /*from_rest=*/true);
    const SimilarityResult coarse = check(Scheme::waf, c, 0.1, {1.8e-2, 4e-3, 2e-3});
    const SimilarityResult fine = check(Scheme::waf, c, 0.05, {1.8e-2, 4e-3, 2e-3});
    EXPECT_GT(std::log2(coarse.l1_relative / fine.l1_relative), 1.2);
}

// The first-order scheme on the SH cap released spreading, down to dx = 0.025 m (160
// cells over the initial cap). With the central-difference regime rule its error fell
// at first order to dx = 0.05 and then rose 8x (E1 1.7e-2 -> 1.3e-1, L_x 12 % too
// wide): passive cells grew in patterns inside the spreading cap. Measured now: E1 =
// 1.68e-2, 8.7e-3 (order 0.94), L_x 1.6 %, 0.8 % too wide. Bound: order >= 0.8 (the
// first-order band of OneDimensionalConvergesAtFirstOrder) and the spread error halves
// at least by 1.6x.
TEST(SimilaritySolution, GodunovSavageHutterConvergesToFineCells) {
    const SimilarityCase c = similarity_1d(EarthPressureModel::savage_hutter);
    const SimilarityResult coarse = run_similarity(c, with_scheme(Scheme::godunov), 0.05);
    const SimilarityResult fine = run_similarity(c, with_scheme(Scheme::godunov), 0.025);
    std::cout << "[similarity] Godunov, SH, E1 " << coarse.l1_relative << " -> " << fine.l1_relative
              << ", L_x " << coarse.l_x << " -> " << fine.l_x << " (exact " << fine.l_x_exact
              << ")\n";
    EXPECT_GT(std::log2(coarse.l1_relative / fine.l1_relative), 0.8);
    EXPECT_GT(std::abs(coarse.l_x - coarse.l_x_exact), 1.6 * std::abs(fine.l_x - fine.l_x_exact));
}

// The first-order scheme on the SH cap released from rest, dx = 0.05 -> 0.025 ->
// 0.0125 m (40 cells per release depth at the finest). History of the regime rule
// (docs/verification.md, finding 2): with unconfirmed compressions taken for active its
// error fell to dx = 0.05 and then rose 5x (E1 1.8e-2 -> 9.3e-2); with the regime kept
// where nothing confirms a compression it stalled (1.84e-2, 1.64e-2) and failed on
// 0.0125 m cells (0.24, L_x 18 % too wide): at its smeared rear edge and front the
// velocity wiggles over a few cells, one of the two confirming scales saw a compression
// there, and the passive cells spread into the body. Since 2026-12-02 (seventh
// session) the first-order scheme's compressions must be confirmed at both scales
// (RegimeRowInput::confirm_at_both_scales): measured E1 1.86e-2, 9.6e-3, 5.0e-3 (orders
// 0.94, 0.95), L_x 1.7 %, 0.86 %, 0.43 % too wide. Bounds: first order on both pairs
// (>= 0.8, the band of the released cap) and the spread error at least 1.6x smaller
// each time (measured 2.0x).
TEST(SimilaritySolution, GodunovSavageHutterFromRestConvergesToCellsOf0125) {
    const SimilarityCase c = similarity_1d(EarthPressureModel::savage_hutter, /*from_rest=*/true);
    std::vector<SimilarityResult> r;
    for (const double dx : {0.05, 0.025, 0.0125}) {
        r.push_back(run_similarity(c, with_scheme(Scheme::godunov), dx));
        std::cout << "[similarity] Godunov, SH, from rest, dx " << dx << ": E1 " << r.back().l1_relative
                  << ", L_x " << r.back().l_x << " (exact " << r.back().l_x_exact << ")\n";
    }
    for (std::size_t k = 1; k < r.size(); ++k) {
        EXPECT_GT(std::log2(r[k - 1].l1_relative / r[k].l1_relative), 0.8) << "pair " << k;
        EXPECT_GT(std::abs(r[k - 1].l_x - r[k - 1].l_x_exact),
                  1.6 * std::abs(r[k].l_x - r[k].l_x_exact))
            << "pair " << k;
    }
}

// Refined one level beyond the other tests (40 cells per release depth): until
// 2026-12-02 (sixth session) a difference with a dry cell counted as one with a cell at
// rest, the last wet cell of the spreading front compressed against the dry ground and
// turned passive, and a period-2 velocity oscillation ran from the front through the
// body: E1 0.24, L_x 7.03 m against 5.82 (docs/verification.md, finding 2). Now such a
// difference extends: measured E1 7.6e-5 (2.0e-3, 7.0e-4, 2.3e-4 at dx 0.1, 0.05, 0.025:
// about second order). Bound: half the error at 0.025 m.
TEST(SimilaritySolution, SavageHutterFromRestConvergesOnCellsOf0125) {
    const SimilarityCase c = similarity_1d(EarthPressureModel::savage_hutter, /*from_rest=*/true);
    const SimilarityResult r = run_similarity(c, with_scheme(Scheme::waf), 0.0125);
    std::cout << "[similarity] WAF, SH, from rest, dx 0.0125: E1 " << r.l1_relative << ", L_x "
              << r.l_x << " (exact " << r.l_x_exact << ")\n";
    EXPECT_LT(r.l1_relative, 1.15e-4);
    EXPECT_LT(std::abs(r.l_x - r.l_x_exact) / r.l_x_exact, 1e-4);
}
