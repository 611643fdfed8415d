#include "support/analytic_dam_break.hpp"

#include <algorithm>
#include <cmath>

#include "support/analytic_quadrature.hpp"

namespace avalanche::analytic {

double DamBreakProblem::m() const {
    return gravity * (std::sin(theta_rad) - std::cos(theta_rad) * std::tan(delta_rad));
}

double DamBreakProblem::c0() const { return std::sqrt(k * gravity * std::cos(theta_rad) * h0); }

double dam_break_front(const DamBreakProblem& p, double t) {
    return 2.0 * p.c0() * t + 0.5 * p.m() * t * t;
}

double dam_break_rear(const DamBreakProblem& p, double t) {
    return -p.c0() * t + 0.5 * p.m() * t * t;
}

DepthVelocity dam_break_exact(const DamBreakProblem& p, double x, double t) {
    if (t <= 0.0) return {x < 0.0 ? p.h0 : 0.0, 0.0};
    const double m = p.m(), c0 = p.c0();
    if (x < dam_break_rear(p, t)) return {p.h0, m * t};
    if (x > dam_break_front(p, t)) return {0.0, 0.0};
    const double w = 2.0 * c0 - x / t + 0.5 * m * t;  // = 3 sqrt(k g cos h)
    return {w * w / (9.0 * p.k * p.gravity * std::cos(p.theta_rad)),
            2.0 / 3.0 * (c0 + x / t + m * t)};
}

double dam_break_position_of_depth(const DamBreakProblem& p, double level, double t) {
    const double a = std::sqrt(p.k * p.gravity * std::cos(p.theta_rad) * level);
    return t * (2.0 * p.c0() + 0.5 * p.m() * t - 3.0 * a);
}

double dam_break_cell_average(const DamBreakProblem& p, double xa, double xb, double t) {
    // h is a polynomial of degree 2 between the kinks x_r and x_f, constant outside:
    // split there and Gauss is exact.
    const double xr = dam_break_rear(p, t), xf = dam_break_front(p, t);
    const auto h = [&](double x) { return dam_break_exact(p, x, t).h; };
    double cuts[4] = {xa, std::clamp(xr, xa, xb), std::clamp(xf, xa, xb), xb};
    if (t <= 0.0) cuts[1] = cuts[2] = std::clamp(0.0, xa, xb);
    double sum = 0.0;
    for (int s = 0; s < 3; ++s) sum += gauss_integral(h, cuts[s], cuts[s + 1]);
    return sum / (xb - xa);
}

}  // namespace avalanche::analytic
