// MODEL.md section 4, grid convergence: observed order of accuracy of both schemes
// on a smooth and on a non-smooth (dam-break) problem. p = log2(E(2 dx) / E(dx)).
//
// Smooth: a Gaussian hump on a layer stretched by u = x (1/s), flat bed, no friction
// (analytic_studies.hpp), isotropic and Savage-Hutter (du/dx > 0 everywhere, so the
// active k throughout), t = 0.5 s, nx = 50, 100, 200 against a WAF reference on 1600
// cells; E = mean |h - h_ref| over [-6, 6] m.
// Non-smooth: the Mangeney dam break (kinks at the rear and a dry front), dx = 0.2,
// 0.1, 0.05 against the exact solution.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "support/analytic_harness.hpp"
#include "support/analytic_studies.hpp"

using namespace avalanche;
using namespace avalanche::analytic;

namespace {

std::vector<double> orders(const std::vector<double>& e) {
    std::vector<double> p;
    for (std::size_t l = 1; l < e.size(); ++l) p.push_back(observed_order(e[l - 1], e[l]));
    return p;
}

void print(const char* what, const std::vector<double>& e) {
    std::cout << "[convergence] " << what << ":";
    for (std::size_t l = 0; l < e.size(); ++l)
        std::cout << " E=" << e[l]
                  << (l ? " (p=" + std::to_string(observed_order(e[l - 1], e[l])) + ")" : "");
    std::cout << "\n";
}

constexpr int kLevels = 3, kCoarse = 50, kRefFactor = 8;  // 50, 100, 200; reference 1600
}  // namespace

// Godunov: first order. The coarsest pair (50 -> 100 cells) is pre-asymptotic
// (measured 0.76 iso, 0.95 SH against the second-order WAF reference; with the earlier
// first-order-accurate reference it read 0.81, the reference's own error inflating it);
// the finest pair must lie in [0.8, 1.3] (measured 0.87 iso, 0.95 SH), every pair > 0.7.
TEST(Convergence, SmoothGodunovIsFirstOrder) {
    for (EarthPressureModel m :
         {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter}) {
        const std::vector<double> e =
            smooth_errors(smooth_hump(m), with_scheme(Scheme::godunov), kCoarse, kLevels, kRefFactor);
        print(smooth_hump(m).name, e);
        const std::vector<double> p = orders(e);
        for (double q : p) EXPECT_GT(q, 0.7);
        EXPECT_GT(p.back(), 0.8);
        EXPECT_LT(p.back(), 1.3);
    }
}

// WAF: second order on smooth flow (MODEL.md: near 2). The outer waves are limited on
// their characteristic strengths (docs/numerics.md); measured p = 1.95, 1.94 (iso) and
// 2.02, 2.00 (SH). Band [1.6, 2.4].
TEST(Convergence, SmoothWafIsSecondOrder) {
    for (EarthPressureModel m :
         {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter}) {
        const SmoothCase c = smooth_hump(m);
        const std::vector<double> w =
            smooth_errors(c, with_scheme(Scheme::waf), kCoarse, kLevels, kRefFactor);
        print(c.name, w);
        for (double p : orders(w)) {
            EXPECT_GT(p, 1.6);
            EXPECT_LT(p, 2.4);
        }
    }
}

// Dam break: the kink at the rear and the quadratic dry front limit L1 convergence.
// Band: WAF in [0.8, 1.3] (measured 1.01, 1.03), Godunov in [0.4, 1.0] (measured
// 0.58, 0.64).
TEST(Convergence, DamBreakOrderAtMostOne) {
    for (Scheme s : {Scheme::waf, Scheme::godunov}) {
        std::vector<double> e;
        for (double dx : {0.2, 0.1, 0.05})
            e.push_back(run_dam_break(dam_break_isotropic(), with_scheme(s), dx).l1_relative);
        print(s == Scheme::waf ? "dam break WAF" : "dam break Godunov", e);
        for (double p : orders(e)) {
            EXPECT_GT(p, s == Scheme::waf ? 0.8 : 0.4);
            EXPECT_LT(p, s == Scheme::waf ? 1.3 : 1.0);
        }
    }
}
