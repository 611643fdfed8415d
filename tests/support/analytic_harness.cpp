#include "support/analytic_harness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace avalanche::analytic {

Grid box_grid(double x_lo, double x_hi, double y_lo, double y_hi, double dx) {
    Grid g;
    g.nx = static_cast<int>(std::lround((x_hi - x_lo) / dx));
    g.ny = static_cast<int>(std::lround((y_hi - y_lo) / dx));
    g.dx = g.dy = dx;
    g.x0 = x_lo;
    g.y0 = y_lo;
    return g;
}

Grid line_grid(double x_lo, double x_hi, double dx) {
    Grid g = box_grid(x_lo, x_hi, 0.0, dx, dx);
    g.ny = 1;
    return g;
}

TerrainFields plane_terrain(const Grid& g, double slope_deg, double gravity) {
    TerrainFields t;
    t.frame = Frame::chute;
    t.allocate(g, false, false);
    const double zeta = slope_deg * std::acos(-1.0) / 180.0;
    for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
            t.ax(i, j) = gravity * std::sin(zeta);
            t.px(i, j) = t.py(i, j) = t.gn(i, j) = gravity * std::cos(zeta);
            t.elevation(i, j) = -g.x_center(i) * std::sin(zeta);
        }
    }
    t.extend_to_ghosts();
    return t;
}

State make_state(const Grid& g, const CellAverage& h, const PointVelocity& uv) {
    State s(g);
    for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
            const double xa = g.x0 + i * g.dx, ya = g.y0 + j * g.dy;
            const double hh = h(xa, xa + g.dx, ya, ya + g.dy);
            s.h(i, j) = hh;
            if (uv && hh > 0.0) {
                const auto [u, v] = uv(g.x_center(i), g.y_center(j));
                s.hu(i, j) = hh * u;
                s.hv(i, j) = hh * v;
            }
        }
    }
    return s;
}

long advance_to(Stepper& stepper, State& s, double t, double t_end) {
    stepper.reset_active_box(s);
    long steps = 0;
    // Same rule as Simulation::run: land on t_end without a sliver step.
    const double eps = 1e-12 * std::max(1.0, t_end);
    while (t < t_end - eps) {
        double dt = stepper.stable_dt(s);
        if (!std::isfinite(dt)) break;
        if (t + dt >= t_end - eps) dt = t_end - t;
        stepper.step(s, dt);
        t += dt;
        ++steps;
    }
    return steps;
}

double l1_depth_error(const State& s, const Grid& g, const CellAverage& exact) {
    long double sum = 0.0L;
    for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
            const double xa = g.x0 + i * g.dx, ya = g.y0 + j * g.dy;
            sum += std::abs(s.h(i, j) - exact(xa, xa + g.dx, ya, ya + g.dy));
        }
    }
    return static_cast<double>(sum) * g.cell_area();
}

Moments depth_moments(const State& s, const Grid& g) {
    long double v = 0.0L, mx = 0.0L, my = 0.0L;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            v += s.h(i, j);
            mx += s.h(i, j) * g.x_center(i);
            my += s.h(i, j) * g.y_center(j);
        }
    Moments m;
    m.volume = static_cast<double>(v) * g.cell_area();
    if (v <= 0.0L) return m;
    m.x_c = static_cast<double>(mx / v);
    m.y_c = static_cast<double>(my / v);
    long double sx = 0.0L, sy = 0.0L;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double ddx = g.x_center(i) - m.x_c, ddy = g.y_center(j) - m.y_c;
            sx += s.h(i, j) * ddx * ddx;
            sy += s.h(i, j) * ddy * ddy;
        }
    m.var_x = static_cast<double>(sx / v);
    m.var_y = static_cast<double>(sy / v);
    return m;
}

double last_x_above(const State& s, const Grid& g, int j, double level) {
    for (int i = g.nx - 1; i >= 0; --i)
        if (s.h(i, j) > level) return g.x_center(i);
    return std::numeric_limits<double>::quiet_NaN();
}

double first_x_below(const State& s, const Grid& g, int j, double level) {
    for (int i = 0; i < g.nx; ++i)
        if (s.h(i, j) < level) return g.x_center(i);
    return std::numeric_limits<double>::quiet_NaN();
}

double mirror_asymmetry(const State& s, const Grid& g) {
    double worst = 0.0;
    for (int j = 0; j < g.ny / 2; ++j)
        for (int i = 0; i < g.nx; ++i)
            worst = std::max(worst, std::abs(s.h(i, j) - s.h(i, g.ny - 1 - j)));
    return worst;
}

double min_depth(const State& s, const Grid& g) {
    double lo = std::numeric_limits<double>::infinity();
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) lo = std::min(lo, s.h(i, j));
    return lo;
}

ScopedThreads::ScopedThreads(int n) {
#ifdef _OPENMP
    saved_ = omp_get_max_threads();
    if (n != kKeep) omp_set_num_threads(n);
#else
    (void)n;
#endif
}

ScopedThreads::~ScopedThreads() {
#ifdef _OPENMP
    omp_set_num_threads(saved_);
#endif
}

double observed_order(double e_coarse, double e_fine, double ratio) {
    return std::log(e_coarse / e_fine) / std::log(ratio);
}

std::vector<double> restrict_row(const std::vector<double>& fine, int factor) {
    std::vector<double> out(fine.size() / static_cast<std::size_t>(factor), 0.0);
    for (std::size_t n = 0; n < out.size(); ++n) {
        double sum = 0.0;
        for (int q = 0; q < factor; ++q) sum += fine[n * factor + q];
        out[n] = sum / factor;
    }
    return out;
}

}  // namespace avalanche::analytic
