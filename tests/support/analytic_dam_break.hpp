#pragma once
// Exact solution of the 1D granular dam break on an inclined plane with Coulomb
// friction (Mangeney, Heinrich & Roche 2000, Pure Appl. Geophys. 157:1081, eqs. 19-21,
// with the earth-pressure coefficient k kept as a factor of the hydrostatic pressure).
//
// Bed-fitted frame, x downslope, bed-normal thickness h. At t = 0 a reservoir of
// depth h0 at rest fills x < 0 and x > 0 is dry. With
//   m  = g (sin(theta) - cos(theta) tan(delta))   (net along-slope acceleration),
//   c0 = sqrt(k g cos(theta) h0)                  (celerity of the reservoir),
// the solution for t > 0 is
//   x <  x_r = -c0 t + m t^2/2 :  h = h0, u = m t              (sliding reservoir)
//   x_r <= x <= x_f = 2 c0 t + m t^2/2 :
//                                  h = (2 c0 - x/t + m t/2)^2 / (9 k g cos(theta)),
//                                  u = 2/3 (c0 + x/t + m t)    (centred rarefaction)
//   x >  x_f :                     h = 0.
// It is the shallow-water rarefaction seen from a frame that accelerates at m; it
// holds while every material point moves downslope (u >= 0, so the friction
// direction is uniform), which is true for all t when m >= 0 (u >= m t).
// The rarefaction extends the flow everywhere (du/dx = 2/(3t) > 0), so in the
// Savage-Hutter model k is the active k_x.
namespace avalanche::analytic {

struct DamBreakProblem {
    double h0 = 1.0;         // reservoir thickness (m, bed-normal)
    double theta_rad = 0.0;  // plane inclination
    double delta_rad = 0.0;  // bed friction angle
    double k = 1.0;          // earth-pressure coefficient (active k_x for SH)
    double gravity = 9.81;   // m/s^2

    [[nodiscard]] double m() const;   // net acceleration g (sin - cos tan delta)
    [[nodiscard]] double c0() const;  // reservoir celerity sqrt(k g cos h0)
};

struct DepthVelocity {
    double h = 0.0;
    double u = 0.0;
};

// Exact h and u at (x, t), t > 0 (at t = 0 the initial step).
DepthVelocity dam_break_exact(const DamBreakProblem& p, double x, double t);

// Exact front and rear (tail of the rarefaction) positions.
double dam_break_front(const DamBreakProblem& p, double t);
double dam_break_rear(const DamBreakProblem& p, double t);

// Position in the rarefaction where the exact depth equals level (0 < level < h0):
// the exact counterpart of "last cell with h > level", which a threshold-based front
// detector measures (the exact depth vanishes quadratically at x_f).
double dam_break_position_of_depth(const DamBreakProblem& p, double level, double t);

// Exact cell average of h over [xa, xb], integrated piecewise between the kinks.
double dam_break_cell_average(const DamBreakProblem& p, double xa, double xb, double t);

}  // namespace avalanche::analytic
