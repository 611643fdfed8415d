// Extreme-case matrix (issue "Speed against accuracy", item 5): the solver must
// survive every corner of the input space a user can reach. Each case asserts
//   - no NaN/Inf and no negative depth: Simulation::run throws NumericalError
//     (caught here and reported as a failure with its cell and time), and an
//     observer checks min h >= 0 after every step;
//   - mass conserved to round-off: |RunStatistics::relative_mass_error()| < 1e-12,
//     the outflow through open edges counted (MODEL.md 2.5);
//   - every speed (true, along-surface, any cell holding material, any step) below
//     the free-fall bound sqrt(u0^2 + 2 g drop) + 2 sqrt(k_max g h0) of the scene
//     (extreme_scenes.hpp says why).
// The checks are run_and_check's (extreme_checks.hpp), shared with the random sweep.
// Cases are sized for CI: the whole executable runs in well under 2 minutes on one thread.
#include <gtest/gtest.h>

#include <optional>
#include <sstream>
#include <vector>

#include "extreme_checks.hpp"
#include "extreme_scenes.hpp"

using namespace avalanche;
using namespace avalanche::extremes;

namespace {

std::string scheme_tag(Scheme s) { return s == Scheme::waf ? "waf" : "god"; }
std::string model_tag(EarthPressureModel m) {
    return m == EarthPressureModel::savage_hutter ? "sh" : "iso";
}

// Decimal value as an identifier fragment: 0.01 -> "0p01", 1e-08 -> "1em08".
std::string tag(double v) {
    std::ostringstream o;
    o << v;
    std::string s = o.str();
    for (char& ch : s) {
        if (ch == '.') ch = 'p';
        if (ch == '-') ch = 'm';
        if (ch == '+') ch = 'p';
    }
    return s;
}

// The matrix: for each scheme and earth-pressure model, one-at-a-time sweeps of
// each parameter from a baseline (30 deg plane, delta 20, phi 35, 1 m release,
// automatic h_min, C = 0.2), plus the special scenes.
std::vector<Case> matrix() {
    std::vector<Case> cases;
    for (Scheme scheme : {Scheme::waf, Scheme::godunov}) {
        for (EarthPressureModel ep :
             {EarthPressureModel::savage_hutter, EarthPressureModel::isotropic}) {
            const std::string suffix = "_" + scheme_tag(scheme) + "_" + model_tag(ep);
            const auto add = [&](Case c, const std::string& name) {
                c.scheme = scheme;
                c.earth_pressure = ep;
                c.name = name + suffix;
                cases.push_back(c);
            };
            for (double slope : {0.0, 15.0, 30.0, 45.0, 60.0, 80.0}) {
                Case c;
                c.kind = Kind::plane_dem;
                c.slope_deg = slope;
                add(c, "dem_plane_slope" + tag(slope));
            }
            for (double slope : {0.0, 45.0, 80.0}) {
                Case c;
                c.kind = Kind::plane_chute;
                c.slope_deg = slope;
                add(c, "chute_plane_slope" + tag(slope));
            }
            // delta from 0 to 45 deg, phi from delta (the limit of the theory, k_x
            // root zero) to 50; phi > 0 is required, so delta = 0 pairs with phi = 1.
            const double friction[][2] = {{0, 1},   {0, 50},  {20, 20}, {20, 50},
                                          {30, 30}, {45, 45}, {45, 50}};
            for (const auto& dp : friction) {
                Case c;
                c.slope_deg = 35.0;
                c.delta_deg = dp[0];
                c.phi_deg = dp[1];
                add(c, "friction_delta" + tag(dp[0]) + "_phi" + tag(dp[1]));
            }
            for (double h0 : {0.01, 0.1, 10.0, 200.0}) {
                Case c;
                c.slope_deg = 35.0;
                c.h0 = h0;
                add(c, "release_h" + tag(h0));
            }
            for (double h_min : {1e-8, 1e-6, 1e-4, 1e-2}) {
                Case c;
                c.h_min = h_min;
                add(c, "h_min_" + tag(h_min));
            }
            for (double cfl : {0.05, 0.5}) {
                Case c;
                c.cfl = cfl;
                add(c, "cfl_" + tag(cfl));
            }
            // S(dt/2) L(dt) S(dt/2) advects the whole step at once: at Courant 0.5 each
            // advection runs at twice the Courant number of L S L's half steps (the
            // draft preset uses it at 0.4, the fine preset at 0.2).
            {
                Case c;
                c.cfl = 0.5;
                c.splitting = Splitting::sls;
                add(c, "cfl_0p5_sls");
                c.kind = Kind::plane_dem;
                c.slope_deg = 80.0;
                add(c, "dem_plane_slope80_cfl_0p5_sls");
            }
            for (int n : {3, 4, 5}) {
                for (double slope : {0.0, 60.0}) {
                    Case c;
                    c.kind = Kind::single_cell;
                    c.n = n;
                    c.slope_deg = slope;
                    add(c, "grid" + std::to_string(n) + "x" + std::to_string(n) + "_slope" +
                               tag(slope));
                }
            }
            for (double h0 : {1.0, 10.0}) {
                Case c;
                c.kind = Kind::cliff_staircase;
                c.h0 = h0;
                c.u0 = 10.0;
                c.delta_deg = 15.0;
                add(c, "cliff_staircase_h" + tag(h0));
                c.cfl = 0.5;
                c.splitting = Splitting::sls;
                add(c, "cliff_staircase_h" + tag(h0) + "_cfl_0p5_sls");
            }
            {
                Case c;
                c.kind = Kind::cliff_up;
                c.h0 = 5.0;
                c.u0 = 30.0;
                add(c, "cliff_wall_ahead");
            }
            for (double delta : {0.0, 20.0}) {
                Case c;
                c.kind = Kind::outflow;
                c.slope_deg = 40.0;
                c.delta_deg = delta;
                add(c, "outflow_delta" + tag(delta));
            }
            for (double u0 : {5.0, 50.0}) {
                Case c;
                c.kind = Kind::collision_flat;
                c.n = 40;
                c.u0 = u0;
                add(c, "collision_flat_u" + tag(u0));
            }
            // numerics.rest_faces where cells come to rest beside moving ones: a deposit on
            // a gentle plane, the steepest and most frictional, a deep release, a pile-up
            // against a cliff, two flows colliding, and S L S at Courant 0.5.
            {
                const auto held = [&](Case c, const std::string& name) {
                    c.rest_faces = true;
                    add(c, name + "_rest_faces");
                };
                Case c;
                c.kind = Kind::plane_dem;
                for (double slope : {0.0, 15.0, 80.0}) {
                    c.slope_deg = slope;
                    held(c, "dem_plane_slope" + tag(slope));
                }
                Case f;
                f.slope_deg = 35.0;
                f.delta_deg = 45.0;
                f.phi_deg = 50.0;
                held(f, "friction_delta45_phi50");
                Case deep;
                deep.slope_deg = 35.0;
                deep.h0 = 200.0;
                held(deep, "release_h200");
                Case cliff;
                cliff.kind = Kind::cliff_up;
                cliff.h0 = 5.0;
                cliff.u0 = 30.0;
                held(cliff, "cliff_wall_ahead");
                Case hit;
                hit.kind = Kind::collision_flat;
                hit.n = 40;
                hit.u0 = 5.0;
                held(hit, "collision_flat_u5");
                hit.cfl = 0.5;
                hit.splitting = Splitting::sls;
                held(hit, "collision_flat_u5_cfl_0p5_sls");
            }
            for (double slope : {30.0, 60.0}) {
                Case c;
                c.kind = Kind::collision_valley;
                c.n = 40;
                c.slope_deg = slope;
                c.h0 = 2.0;
                add(c, "collision_valley_slope" + tag(slope));
                c.cfl = 0.5;
                c.splitting = Splitting::sls;
                add(c, "collision_valley_slope" + tag(slope) + "_cfl_0p5_sls");
            }
        }
    }
    return cases;
}

}  // namespace

namespace avalanche::extremes {
// gtest prints a failing parameter with this instead of its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }
}  // namespace avalanche::extremes

namespace {

class Extremes : public ::testing::TestWithParam<Case> {};

TEST_P(Extremes, FiniteNonNegativeConservativeAndBelowFreeFall) {
    const Case& c = GetParam();
    const std::optional<RunStatistics> st = run_and_check(make_scene(c), "[extremes] " + c.name);
    ASSERT_TRUE(st.has_value());
    if (c.kind == Kind::outflow) {
        EXPECT_GT(st->outflow_volume, 0.0)
            << "the release next to the open edge must leave through it";
    }
}

INSTANTIATE_TEST_SUITE_P(Matrix, Extremes, ::testing::ValuesIn(matrix()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                             return info.param.name;
                         });

}  // namespace
