#pragma once
// The Savage-Hutter similarity solution (Savage & Hutter 1991, Acta Mech. 86:201;
// Hutter, Siegel, Savage & Nohguchi 1993, Acta Mech. 100:37): a parabolic cap
// [1D] or paraboloid [2D] that slides down a plane of inclination theta while it
// spreads, keeping its shape.
//
// Derivation (bed-fitted frame, constant theta, MODEL.md section 1 with
// k_x, k_y constant, g_z = g cos(theta)). Ansatz
//   h = H(t) (1 - xi^2 - eta^2),  xi = (x - x_c(t)) / L_x(t),  eta = (y - y_c) / L_y(t),
//   u = x_c' + xi L_x',  v = eta L_y'                      (drop eta, v, L_y in 1D).
// Then D(xi)/Dt = (u - x_c')/L_x - xi L_x'/L_x = 0 and likewise D(eta)/Dt = 0: xi, eta
// are material coordinates. Mass: Dh/Dt + h (u_x + v_y) = 0 gives
//   H' (1 - xi^2 - eta^2) + H (1 - xi^2 - eta^2) (L_x'/L_x + L_y'/L_y) = 0
//   =>  H L_x L_y = const  (2D),  H L_x = const (1D).
// x-momentum: Du/Dt = x_c'' + xi L_x'' must equal
//   g sin(theta) - (u/|u|) tan(delta) g cos(theta) - k_x g cos(theta) h_x,
// with h_x = -2 H xi / L_x. If every material point moves downslope (u > 0, v = 0 in
// 1D) the friction term is the constant tan(delta) g cos(theta), and matching the
// xi^0 and xi^1 terms gives
//   x_c'' = g (sin(theta) - cos(theta) tan(delta)),   L_x'' = 2 k_x g cos(theta) H / L_x,
// and in y (no gravity along y): y_c'' = 0, L_y'' = 2 k_y g cos(theta) H / L_y.
// In 2D the friction direction (u, v)/|(u, v)| varies over the cap unless v = 0, so
// the 2D solution is exact only for delta = 0 (or where that direction is uniform).
// Conditions: 1D with delta > 0 needs u > 0 at the rear (xi = -1) for all t, i.e.
// x_c' >= L_x'; starting from rest this holds while x_c'' >= L_x'', i.e. when
// m >= 2 k_x g cos(theta) H0 / L0 (checked by similarity_valid()).
// Which k: the cap spreads, u_x = L_x'/L_x > 0 and v_y = L_y'/L_y > 0 everywhere, so
// the Savage-Hutter k_x and k_y are the ACTIVE ones (and k_y is the one given an
// active k_x). With delta = 0 they reduce to Rankine's k = (1 - sin phi)/(1 + sin phi).
//
// The ODE system (x_c, x_c', L_x, L_x', L_y, L_y') is integrated with classical RK4
// at a fixed step of 1e-4 s: its global error ~ (1e-4)^4 x O(1) is far below 1e-10
// (checked by a test that halves the step).
namespace avalanche::analytic {

struct SimilarityProblem {
    bool two_d = false;
    double theta_rad = 0.0;
    double delta_rad = 0.0;     // must be 0 in 2D
    double kx = 1.0, ky = 1.0;  // active earth-pressure coefficients (constant)
    double gravity = 9.81;
    double x_c0 = 0.0, y_c0 = 0.0;    // initial centre (m)
    double u_c0 = 0.0;                // initial centre velocity (m/s)
    double l_x0 = 1.0, l_y0 = 1.0;    // initial half-lengths (m)
    double dl_x0 = 0.0, dl_y0 = 0.0;  // initial spreading rates (m/s)
    double h_0 = 0.1;                 // initial centre thickness (m)
};

struct SimilarityState {
    double x_c = 0.0, u_c = 0.0;   // centre and its velocity
    double l_x = 1.0, dl_x = 0.0;  // half-length along x and its rate
    double l_y = 1.0, dl_y = 0.0;  // half-width along y and its rate (2D)
    double h = 0.0;                // centre thickness H(t)
    double y_c = 0.0;
};

// The similarity parameters at time t (RK4 with step `step`).
SimilarityState similarity_at(const SimilarityProblem& p, double t, double step = 1e-4);

// Exact thickness and velocity at a point.
double similarity_depth(const SimilarityProblem& p, const SimilarityState& s, double x, double y);
double similarity_u(const SimilarityState& s, double x);
double similarity_v(const SimilarityState& s, double y);

// Exact cell average of h over [xa, xb] x [ya, yb] (in 1D the y range is ignored).
double similarity_cell_average(const SimilarityProblem& p, const SimilarityState& s, double xa,
                               double xb, double ya, double yb);

// Whether the 1D/2D hypotheses hold on [0, t_end] (all material moves downslope;
// delta = 0 in 2D): the rear velocity x_c' - L_x' stays >= 0.
bool similarity_valid(const SimilarityProblem& p, double t_end);

}  // namespace avalanche::analytic
