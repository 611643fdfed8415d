#pragma once
// The verification cases of MODEL.md section 4 as functions of the numerics and
// the cell size, shared by tests/verification (few small levels, asserted) and
// tools/verification_report (more levels, all limiters, tabulated in
// docs/verification.md). Each returns error norms, never fields (STYLE.md 11).
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/physics/material.hpp"
#include "support/analytic_dam_break.hpp"
#include "support/analytic_similarity.hpp"

namespace avalanche::analytic {

// ---------------------------------------------------------------- dam break
struct DamBreakCase {
    const char* name = "";
    DamBreakProblem exact;
    MaterialParams material;
    double t_end = 2.0;
    double x_lo = -14.0, x_hi = 20.0;  // wall at x_lo, > 2 c0 t_end behind the dam
    double front_level = 1e-2;         // front = last cell with h > level x h0
    double rear_level = 0.99;          // rear = first cell with h < level x h0
};
// Isotropic k = 1 on 35 deg with delta = 20 deg (m = 2.70 m/s^2); isotropic on 30 deg
// with delta = 30 deg (m = 0: friction balances gravity, the reservoir stays, Ritter's
// solution); Savage-Hutter (phi = 35, delta = 20 deg) compared with the active k_x
// (the rarefaction extends everywhere; the reservoir at rest is a tie, see
// docs/verification.md).
DamBreakCase dam_break_isotropic();
DamBreakCase dam_break_balanced();
DamBreakCase dam_break_savage_hutter();

struct DamBreakResult {
    double dx = 0.0;
    double l1_relative = 0.0;               // int |h - h_exact| dx / (h0 (x_f - x_r))
    double front = 0.0, front_exact = 0.0;  // at h = front_level h0
    double rear = 0.0, rear_exact = 0.0;    // at h = rear_level h0
    double mass_error = 0.0;                // relative volume change (walls: must be round-off)
    double solver_seconds = 0.0;            // CPU time of the time loop (s, one thread)
};
DamBreakResult run_dam_break(const DamBreakCase& c, const NumericsParams& n, double dx);

// ---------------------------------------------------------------- similarity
struct SimilarityCase {
    const char* name = "";
    SimilarityProblem exact;
    MaterialParams material;
    double t_end = 2.0;
    double x_lo = 0.0, x_hi = 30.0, y_lo = 0.0, y_hi = 0.0;  // y range 2D only
    double slope_deg = 0.0;
};
// 1D: 35 deg plane, delta = 20 deg, a cap L0 = 4 m, H0 = 0.5 m. 2D: 20 deg plane,
// delta = 0, paraboloid L0 = 3 m, H0 = 0.3 m. Isotropic or Savage-Hutter (active k,
// phi = 35 deg). Released either already spreading (x_c' = 2 m/s in 1D, L' = 1 m/s:
// du/dx = 0.25 1/s > 0 everywhere from the start, so the SH regime is unambiguous)
// or from rest (du/dx = 0 at t = 0: the solver's tie rule picks active, and the noise
// of the scheme decides the regime early on; docs/verification.md, finding 2).
SimilarityCase similarity_1d(EarthPressureModel model, bool from_rest = false);
SimilarityCase similarity_2d(EarthPressureModel model, bool from_rest = false);

struct SimilarityResult {
    double dx = 0.0;
    double l1_relative = 0.0;  // int |h - h_exact| dA / volume
    double x_c = 0.0, x_c_exact = 0.0;
    double l_x = 0.0, l_x_exact = 0.0;  // from the variance: L_x^2 = 5 var (1D), 6 var (2D)
    double l_y = 0.0, l_y_exact = 0.0;
    double mean_u = 0.0, mean_u_exact = 0.0;  // momentum / volume vs x_c'
    double solver_seconds = 0.0;                // CPU time of the time loop (s, one thread)
};
SimilarityResult run_similarity(const SimilarityCase& c, const NumericsParams& n, double dx);

// ---------------------------------------------------------------- smooth flow
// A Gaussian hump on a layer that is stretched by a linear velocity u = a x on a
// flat bed without friction (delta = 0): smooth for the time run, and du/dx > 0
// everywhere so the Savage-Hutter k stays the active one (no switch of the flux
// function). Open edges with supersonic outflow (|u| > a_x there) reflect nothing.
// All studies run on one OpenMP thread (ScopedThreads): see analytic_harness.hpp.
struct SmoothCase {
    const char* name = "";
    MaterialParams material;
    // Edges at +-10 m: the outflow u = x / (1 + t) stays faster than even the passive
    // Savage-Hutter celerity there. (The ghost cells of an open edge copy the edge
    // cell, so their du/dx = 0 and the solver gives them k_pass; with +-6 m the SH
    // edge was subcritical for k_pass and reflected: E1 stalled at 7e-2.)
    double x_lo = -10.0, x_hi = 10.0;
    double base = 1.0, amplitude = 0.3, width = 1.5;  // m
    double stretch = 1.0;                             // 1/s
    double t_end = 0.5;
};
SmoothCase smooth_hump(EarthPressureModel model);
// The depth row on nx cells.
std::vector<double> run_smooth(const SmoothCase& c, const NumericsParams& n, int nx);
// L1 error (m^2 per unit width / domain length = mean absolute depth error) of each
// level nx = n0, 2 n0, ... against a WAF/van Leer reference on ref_factor x the
// finest level, averaged onto each level.
std::vector<double> smooth_errors(const SmoothCase& c, const NumericsParams& n, int n0, int levels,
                                  int ref_factor);

// A material of the studies: phi, delta (deg) and the earth-pressure model.
MaterialParams material(EarthPressureModel model, double phi_deg, double delta_deg);

// ---------------------------------------------------------------- rigid block / creep
// A paraboloid of height H and radius R centred on (0, 0), at rest: cell averages of
// 4 x 4 samples.
State paraboloid_at_rest(const Grid& g, double height, double radius);
struct CreepResult {
    double front_shift = 0.0;   // outward move of the wet edge (h > 1e-3 H) (m)
    double radius_shift = 0.0;  // change of sqrt(6 var) (m), the spread of the paraboloid
    double max_speed = 0.0;     // largest |u| at the end (m/s)
};
// A wide low paraboloid (R = 10 m, H = 0.5 m: surface slope <= 0.1 < tan(delta)/k)
// on a flat bed, delta = 20 deg, at rest, run for t_end.
CreepResult run_creep(const NumericsParams& n, EarthPressureModel model, double dx, double t_end);

}  // namespace avalanche::analytic
