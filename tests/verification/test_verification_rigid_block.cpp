// MODEL.md section 4, rigid-block limit: the centroid of a mass on a plane
// accelerates at g (sin(theta) - cos(theta) tan(delta)); a uniform layer on a plane
// gentler than delta stays exactly at rest; a gentle pile's creep is measured.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "avalanche/numerics/stepper.hpp"
#include "support/analytic_harness.hpp"
#include "support/analytic_rigid_block.hpp"
#include "support/analytic_studies.hpp"

using namespace avalanche;
using namespace avalanche::analytic;

namespace {
NumericsParams numerics(Scheme s, Boundary b = Boundary::open) {
    NumericsParams n;
    n.scheme = s;
    n.boundary = b;
    return n;
}
}  // namespace

// The 1D caps of the similarity test satisfy the rigid-block hypothesis (all material
// moves downslope all the time), so the centroid must follow x0 + u0 t + m t^2/2 with
// m = 2.70 m/s^2 (35 deg, delta 20 deg) whatever k. Norm: the mean acceleration
// a = 2 (x_c(T) - x_c0 - u0 T) / T^2 over T = 2 s, relative to m. Bound 1e-3: the
// centroid is measured on cell centres of a 0.1 m grid, and moves 9.4 m; measured
// |error| <= 2.6e-4 (docs/verification.md). The mean velocity (momentum / volume)
// changes only by gravity and friction, which are uniform here, and by the two
// non-conservative momentum steps at the thin edges (thin-layer velocity reassignment,
// invariant-domain clamp): measured 1.9e-6 to 7.8e-6 relative, bound 2e-5.
TEST(RigidBlock, CentroidAcceleration) {
    for (Scheme s : {Scheme::waf, Scheme::godunov}) {
        for (const SimilarityCase& c :
             {similarity_1d(EarthPressureModel::isotropic, /*from_rest=*/true),
              similarity_1d(EarthPressureModel::savage_hutter)}) {
            const SimilarityResult r = run_similarity(c, numerics(s), 0.1);
            const double m =
                rigid_block_acceleration(c.exact.theta_rad, c.exact.delta_rad, c.exact.gravity);
            const double t = c.t_end;
            const double a = 2.0 * (r.x_c - c.exact.x_c0 - c.exact.u_c0 * t) / (t * t);
            std::cout << "[rigid block] " << (s == Scheme::waf ? "WAF" : "Godunov") << ", "
                      << c.name << ": centroid acceleration " << a << " vs " << m << " (rel "
                      << (a - m) / m << "), mean u " << r.mean_u << " vs " << c.exact.u_c0 + m * t
                      << "\n";
            EXPECT_LT(std::abs(a - m) / m, 1e-3);
            EXPECT_LT(std::abs(r.mean_u - (c.exact.u_c0 + m * t)) / (c.exact.u_c0 + m * t), 2e-5);
        }
    }
}

// A uniform layer covering the whole domain on a 15 deg plane with delta = 20 deg:
// every flux difference is exactly zero and friction (f = tan(delta) g cos dt >
// g sin dt) stops the gravity increment every step. Bitwise: h, hu, hv unchanged over
// 500 steps, for both schemes, both earth-pressure models, open and wall edges.
TEST(RigidBlock, UniformLayerGentlerThanDeltaStaysExactlyAtRest) {
    const ScopedThreads serial(1);  // see analytic_harness.hpp
    const Grid g = box_grid(0.0, 20.0, 0.0, 10.0, 1.0);
    const TerrainFields terrain = plane_terrain(g, 15.0, 9.81);
    for (Scheme s : {Scheme::waf, Scheme::godunov}) {
        for (Boundary b : {Boundary::open, Boundary::wall}) {
            for (EarthPressureModel model :
                 {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter}) {
                MaterialParams mat;
                mat.delta_deg = 20.0;
                mat.earth_pressure = model;
                constexpr double kDepth = 1.3;
                State st = make_state(g, [](double, double, double, double) { return kDepth; });
                Stepper stepper(g, terrain, mat, numerics(s, b), 1e-5 * kDepth);
                stepper.reset_active_box(st);
                for (int n = 0; n < 500; ++n) stepper.step(st, stepper.stable_dt(st));
                int moved = 0;
                for (int j = 0; j < g.ny; ++j)
                    for (int i = 0; i < g.nx; ++i)
                        moved += st.h(i, j) != kDepth || st.hu(i, j) != 0.0 || st.hv(i, j) != 0.0;
                EXPECT_EQ(moved, 0) << "scheme " << static_cast<int>(s) << ", boundary "
                                    << static_cast<int>(b) << ", model " << static_cast<int>(model);
                EXPECT_EQ(stepper.outflow_volume(), 0.0);
            }
        }
    }
}

// A wide low paraboloid (R = 10 m, H = 0.4 m, surface slope <= 0.08 < tan(delta)/k_pass
// = 0.106) on a flat bed, at rest: physically it never moves. The paper's scheme is not
// well-balanced for Coulomb friction (MODEL.md 2.4): the pressure fluxes of the second
// half-step of advection set the pile in motion before friction acts again, so it
// creeps; and the HLL mass flux between two cells at rest with different depths is
// -a/2 (h_R - h_L), a numerical diffusion of the depth that friction cannot stop.
// Measured over 30 s on 0.5 m cells (docs/verification.md): the 1e-3 H edge moves
// 2.5-3.5 m (WAF) and 4 m (Godunov), the variance radius grows 1.6-1.7 m (WAF) and
// 3.7-5.2 m (Godunov), the pile still moves at ~0.01 m/s. The bounds are ~1.5x the
// measured creep, so that a worse regression fails; the numbers are printed.
TEST(RigidBlock, GentlePileCreepIsBounded) {
    for (Scheme s : {Scheme::waf, Scheme::godunov}) {
        for (EarthPressureModel model :
             {EarthPressureModel::isotropic, EarthPressureModel::savage_hutter}) {
            const CreepResult r = run_creep(numerics(s), model, 0.5, 30.0);
            std::cout << "[creep] " << (s == Scheme::waf ? "WAF" : "Godunov") << ", model "
                      << (model == EarthPressureModel::isotropic ? "isotropic" : "Savage-Hutter")
                      << ": front moved " << r.front_shift << " m, radius (from variance) "
                      << r.radius_shift << " m, max speed at 30 s " << r.max_speed << " m/s\n";
            EXPECT_LE(r.front_shift, 6.0);
            EXPECT_LT(std::abs(r.radius_shift), s == Scheme::waf ? 2.6 : 8.0);
            EXPECT_LT(r.max_speed, 0.03);
        }
    }
}
