#include "support/analytic_similarity.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "support/analytic_quadrature.hpp"

namespace avalanche::analytic {

namespace {
using Vec = std::array<double, 6>;  // x_c, u_c, l_x, dl_x, l_y, dl_y

Vec rhs(const SimilarityProblem& p, const Vec& y) {
    const double gc = p.gravity * std::cos(p.theta_rad);
    const double m = p.gravity * std::sin(p.theta_rad) - gc * std::tan(p.delta_rad);
    // Volume invariant: H L_x L_y = H0 L_x0 L_y0 (2D), H L_x = H0 L_x0 (1D).
    const double h = p.two_d ? p.h_0 * p.l_x0 * p.l_y0 / (y[2] * y[4]) : p.h_0 * p.l_x0 / y[2];
    Vec d{};
    d[0] = y[1];
    d[1] = m;
    d[2] = y[3];
    d[3] = 2.0 * p.kx * gc * h / y[2];
    if (p.two_d) {
        d[4] = y[5];
        d[5] = 2.0 * p.ky * gc * h / y[4];
    }
    return d;
}

Vec axpy(const Vec& y, double a, const Vec& k) {
    Vec r;
    for (std::size_t n = 0; n < r.size(); ++n) r[n] = y[n] + a * k[n];
    return r;
}
}  // namespace

SimilarityState similarity_at(const SimilarityProblem& p, double t, double step) {
    Vec y{p.x_c0, p.u_c0, p.l_x0, p.dl_x0, p.l_y0, p.dl_y0};
    const int n = std::max(1, static_cast<int>(std::ceil(t / step)));
    const double dt = t / n;
    for (int s = 0; s < n && t > 0.0; ++s) {
        const Vec k1 = rhs(p, y);
        const Vec k2 = rhs(p, axpy(y, 0.5 * dt, k1));
        const Vec k3 = rhs(p, axpy(y, 0.5 * dt, k2));
        const Vec k4 = rhs(p, axpy(y, dt, k3));
        for (std::size_t c = 0; c < y.size(); ++c)
            y[c] += dt / 6.0 * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c]);
    }
    SimilarityState s;
    s.x_c = y[0];
    s.u_c = y[1];
    s.l_x = y[2];
    s.dl_x = y[3];
    s.l_y = p.two_d ? y[4] : p.l_y0;
    s.dl_y = p.two_d ? y[5] : 0.0;
    s.h = p.two_d ? p.h_0 * p.l_x0 * p.l_y0 / (s.l_x * s.l_y) : p.h_0 * p.l_x0 / s.l_x;
    s.y_c = p.y_c0;
    return s;
}

double similarity_depth(const SimilarityProblem& p, const SimilarityState& s, double x, double y) {
    const double xi = (x - s.x_c) / s.l_x;
    const double eta = p.two_d ? (y - s.y_c) / s.l_y : 0.0;
    return s.h * std::max(0.0, 1.0 - xi * xi - eta * eta);
}

double similarity_u(const SimilarityState& s, double x) {
    return s.u_c + (x - s.x_c) / s.l_x * s.dl_x;
}

double similarity_v(const SimilarityState& s, double y) { return (y - s.y_c) / s.l_y * s.dl_y; }

double similarity_cell_average(const SimilarityProblem& p, const SimilarityState& s, double xa,
                               double xb, double ya, double yb) {
    if (!p.two_d) {
        // A parabola between the edges x_c -/+ L_x: split there and Gauss is exact.
        const double e0 = std::clamp(s.x_c - s.l_x, xa, xb), e1 = std::clamp(s.x_c + s.l_x, xa, xb);
        const auto h = [&](double x) { return similarity_depth(p, s, x, 0.0); };
        return gauss_integral(h, e0, e1) / (xb - xa);
    }
    // 2D: along x exact between the edge chord of the ellipse at each Gauss y.
    const auto row = [&](double y) {
        const double eta = (y - s.y_c) / s.l_y;
        const double w = 1.0 - eta * eta;
        if (w <= 0.0) return 0.0;
        const double half = s.l_x * std::sqrt(w);
        const double e0 = std::clamp(s.x_c - half, xa, xb), e1 = std::clamp(s.x_c + half, xa, xb);
        return gauss_integral([&](double x) { return similarity_depth(p, s, x, y); }, e0, e1);
    };
    // Along y the integrand has a square-root edge; split at the ellipse's y-extent
    // and sub-divide so that the quadrature error stays far below the schemes' errors.
    const double f0 = std::clamp(s.y_c - s.l_y, ya, yb), f1 = std::clamp(s.y_c + s.l_y, ya, yb);
    double sum = 0.0;
    constexpr int kParts = 4;
    for (int q = 0; q < kParts; ++q) {
        const double a = f0 + (f1 - f0) * q / kParts, b = f0 + (f1 - f0) * (q + 1) / kParts;
        sum += gauss_integral(row, a, b);
    }
    return sum / ((xb - xa) * (yb - ya));
}

bool similarity_valid(const SimilarityProblem& p, double t_end) {
    if (p.two_d && p.delta_rad != 0.0) return false;
    if (p.delta_rad == 0.0) return true;  // no friction: direction irrelevant
    constexpr int kSamples = 200;
    for (int n = 0; n <= kSamples; ++n) {
        const SimilarityState s = similarity_at(p, t_end * n / kSamples);
        if (s.u_c - s.dl_x < 0.0) return false;
    }
    return true;
}

}  // namespace avalanche::analytic
