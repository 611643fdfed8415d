#include "support/analytic_studies.hpp"

#include <algorithm>
#include <ctime>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "avalanche/core/simulation.hpp"
#include "avalanche/numerics/stepper.hpp"
#include "avalanche/physics/earth_pressure.hpp"
#include "support/analytic_harness.hpp"
#include "support/analytic_quadrature.hpp"

namespace avalanche::analytic {

namespace {

// CPU time of the time loop alone (the exact solutions' quadrature is not the
// solver's cost), for the speed/accuracy study (tools/pareto_study.cpp). CPU time, not
// wall time: the studies run on one thread, and on a shared machine the wall time
// includes whatever else ran.
double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kG = 9.81;


// The active k_x of a material (1 for the isotropic model).
double active_kx(const MaterialParams& m) { return earth_pressure_coefficients(m).kx_active; }
double active_ky(const MaterialParams& m) { return earth_pressure_coefficients(m).ky(true, true); }

NumericsParams with_boundary(NumericsParams n, Boundary b, double gravity) {
    n.boundary = b;
    n.gravity = gravity;
    return n;
}
}  // namespace

// ---------------------------------------------------------------- dam break

namespace {
DamBreakCase dam_break_case(const char* name, EarthPressureModel model, double slope_deg,
                            double delta_deg) {
    DamBreakCase c;
    c.name = name;
    c.material = material(model, 35.0, delta_deg);
    c.exact.h0 = 1.0;
    c.exact.theta_rad = slope_deg * kDeg;
    c.exact.delta_rad = delta_deg * kDeg;
    c.exact.k = active_kx(c.material);
    c.exact.gravity = kG;
    c.t_end = 2.0;
    // The wall's own rarefaction (the reservoir slides away from it) has its head at
    // x_lo + c0 t + m t^2/2; x_lo = -3 c0 t keeps it c0 t behind the rear x_r.
    c.x_lo = -std::ceil(3.0 * c.exact.c0() * c.t_end + 1.0);
    c.x_hi = std::ceil(dam_break_front(c.exact, c.t_end) + 3.0);
    return c;
}
}  // namespace

DamBreakCase dam_break_isotropic() {
    return dam_break_case("isotropic, 35 deg, delta 20 deg", EarthPressureModel::isotropic, 35.0,
                          20.0);
}
DamBreakCase dam_break_balanced() {
    return dam_break_case("isotropic, 30 deg, delta 30 deg (m = 0)", EarthPressureModel::isotropic,
                          30.0, 30.0);
}
DamBreakCase dam_break_savage_hutter() {
    return dam_break_case("Savage-Hutter, 35 deg, delta 20 deg", EarthPressureModel::savage_hutter,
                          35.0, 20.0);
}

DamBreakResult run_dam_break(const DamBreakCase& c, const NumericsParams& n, double dx) {
    const ScopedThreads serial(1);  // one grid row
    const Grid g = line_grid(c.x_lo, c.x_hi, dx);
    const TerrainFields terrain = plane_terrain(g, c.exact.theta_rad / kDeg, c.exact.gravity);
    State s = make_state(g, [&](double xa, double xb, double, double) {
        return dam_break_cell_average(c.exact, xa, xb, 0.0);
    });
    const NumericsParams num = with_boundary(n, Boundary::wall, c.exact.gravity);
    Stepper stepper(g, terrain, c.material, num, effective_h_min(num, s, terrain));
    const double v0 = total_volume(s, g);
    const double t0 = cpu_seconds();
    advance_to(stepper, s, 0.0, c.t_end);
    const double solver_seconds = cpu_seconds() - t0;

    DamBreakResult r;
    r.solver_seconds = solver_seconds;
    r.dx = dx;
    const double t = c.t_end;
    // Judged on x >= x_w = x_r - c0 t / 2, halfway between the rear and the head of the
    // wall's rarefaction (x_r - c0 t or further back), where the infinite-reservoir
    // solution holds.
    const double x_w = dam_break_rear(c.exact, t) - 0.5 * c.exact.c0() * t;
    double l1 = 0.0;
    r.rear = std::numeric_limits<double>::quiet_NaN();
    for (int i = 0; i < g.nx; ++i) {
        const double xa = g.x0 + i * dx;
        if (xa < x_w) continue;
        l1 += std::abs(s.h(i, 0) - dam_break_cell_average(c.exact, xa, xa + dx, t)) * dx;
        if (std::isnan(r.rear) && s.h(i, 0) < c.rear_level * c.exact.h0) r.rear = g.x_center(i);
    }
    const double fan = dam_break_front(c.exact, t) - dam_break_rear(c.exact, t);
    r.l1_relative = l1 / (c.exact.h0 * fan);
    r.front = last_x_above(s, g, 0, c.front_level * c.exact.h0);
    r.front_exact = dam_break_position_of_depth(c.exact, c.front_level * c.exact.h0, t);
    r.rear_exact = dam_break_position_of_depth(c.exact, c.rear_level * c.exact.h0, t);
    r.mass_error = (total_volume(s, g) - v0) / v0;
    return r;
}

// ---------------------------------------------------------------- similarity

SimilarityCase similarity_1d(EarthPressureModel model, bool from_rest) {
    SimilarityCase c;
    c.name = model == EarthPressureModel::isotropic
                 ? (from_rest ? "1D cap from rest, isotropic" : "1D cap, isotropic")
                 : (from_rest ? "1D cap from rest, Savage-Hutter" : "1D cap, Savage-Hutter");
    c.material = material(model, 35.0, 20.0);
    c.slope_deg = 35.0;
    c.exact.two_d = false;
    c.exact.theta_rad = 35.0 * kDeg;
    c.exact.delta_rad = 20.0 * kDeg;
    c.exact.kx = active_kx(c.material);
    c.exact.gravity = kG;
    c.exact.x_c0 = 8.0;
    c.exact.l_x0 = 4.0;
    c.exact.h_0 = 0.5;
    c.exact.u_c0 = from_rest ? 0.0 : 2.0;
    c.exact.dl_x0 = from_rest ? 0.0 : 1.0;
    c.t_end = 2.0;
    c.x_lo = 0.0;
    c.x_hi = 36.0;
    return c;
}

SimilarityCase similarity_2d(EarthPressureModel model, bool from_rest) {
    SimilarityCase c;
    c.name = model == EarthPressureModel::isotropic
                 ? (from_rest ? "2D paraboloid from rest, isotropic" : "2D paraboloid, isotropic")
                 : (from_rest ? "2D paraboloid from rest, Savage-Hutter"
                              : "2D paraboloid, Savage-Hutter");
    c.material = material(model, 35.0, 0.0);  // delta = 0: uniform (no) friction
    c.slope_deg = 20.0;
    c.exact.two_d = true;
    c.exact.theta_rad = 20.0 * kDeg;
    c.exact.delta_rad = 0.0;
    c.exact.kx = active_kx(c.material);
    c.exact.ky = active_ky(c.material);
    c.exact.gravity = kG;
    c.exact.x_c0 = 7.0;
    c.exact.y_c0 = 0.0;
    c.exact.l_x0 = c.exact.l_y0 = 3.0;
    c.exact.dl_x0 = c.exact.dl_y0 = from_rest ? 0.0 : 1.0;
    c.exact.h_0 = 0.3;
    c.t_end = 1.5;
    c.x_lo = 0.0;
    c.x_hi = 20.0;
    c.y_lo = -8.0;
    c.y_hi = 8.0;
    return c;
}

SimilarityResult run_similarity(const SimilarityCase& c, const NumericsParams& n, double dx) {
    if (!similarity_valid(c.exact, c.t_end))
        throw std::logic_error("similarity case outside the hypotheses of the exact solution");
    const bool two_d = c.exact.two_d;
    const ScopedThreads serial(1);
    const Grid g =
        two_d ? box_grid(c.x_lo, c.x_hi, c.y_lo, c.y_hi, dx) : line_grid(c.x_lo, c.x_hi, dx);
    const TerrainFields terrain = plane_terrain(g, c.slope_deg, c.exact.gravity);
    const SimilarityState s0 = similarity_at(c.exact, 0.0);
    State s = make_state(
        g,
        [&](double xa, double xb, double ya, double yb) {
            return similarity_cell_average(c.exact, s0, xa, xb, ya, yb);
        },
        [&](double x, double y) {
            return std::pair{similarity_u(s0, x), two_d ? similarity_v(s0, y) : 0.0};
        });
    const NumericsParams num = with_boundary(n, Boundary::open, c.exact.gravity);
    Stepper stepper(g, terrain, c.material, num, effective_h_min(num, s, terrain));
    const double t0 = cpu_seconds();
    advance_to(stepper, s, 0.0, c.t_end);
    const double solver_seconds = cpu_seconds() - t0;

    const SimilarityState se = similarity_at(c.exact, c.t_end);
    const Moments m = depth_moments(s, g);
    SimilarityResult r;
    r.solver_seconds = solver_seconds;
    r.dx = dx;
    r.l1_relative = l1_depth_error(s, g,
                                   [&](double xa, double xb, double ya, double yb) {
                                       return similarity_cell_average(c.exact, se, xa, xb, ya, yb);
                                   }) /
                    m.volume;
    r.x_c = m.x_c;
    r.x_c_exact = se.x_c;
    const double shape = two_d ? 6.0 : 5.0;  // L^2 = shape x variance of the cap
    r.l_x = std::sqrt(shape * m.var_x);
    r.l_x_exact = se.l_x;
    r.l_y = two_d ? std::sqrt(shape * m.var_y) : 0.0;
    r.l_y_exact = two_d ? se.l_y : 0.0;
    long double mom = 0.0L;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) mom += s.hu(i, j);
    r.mean_u = static_cast<double>(mom * g.cell_area()) / m.volume;
    r.mean_u_exact = se.u_c;
    return r;
}

// ---------------------------------------------------------------- smooth flow

SmoothCase smooth_hump(EarthPressureModel model) {
    SmoothCase c;
    c.name = model == EarthPressureModel::isotropic ? "stretched hump, isotropic"
                                                    : "stretched hump, Savage-Hutter";
    c.material = material(model, 35.0, 0.0);
    return c;
}

std::vector<double> run_smooth(const SmoothCase& c, const NumericsParams& n, int nx) {
    const ScopedThreads serial(1);  // one grid row
    const double dx = (c.x_hi - c.x_lo) / nx;
    const Grid g = line_grid(c.x_lo, c.x_hi, dx);
    const TerrainFields terrain = plane_terrain(g, 0.0, kG);
    const auto depth = [&](double x) {
        return c.base + c.amplitude * std::exp(-(x * x) / (c.width * c.width));
    };
    State s = make_state(
        g,
        [&](double xa, double xb, double, double) {
            return gauss_integral(depth, xa, xb) / (xb - xa);
        },
        [&](double x, double) {
            return std::pair{c.stretch * x, 0.0};
        });
    // Momentum as the cell average of h u (not h_avg x u(centre)), so that the
    // initial data are second-order accurate too.
    for (int i = 0; i < g.nx; ++i) {
        const double xa = g.x0 + i * dx;
        s.hu(i, 0) =
            gauss_integral([&](double x) { return depth(x) * c.stretch * x; }, xa, xa + dx) / dx;
    }
    const NumericsParams num = with_boundary(n, Boundary::open, kG);
    Stepper stepper(g, terrain, c.material, num, effective_h_min(num, s, terrain));
    advance_to(stepper, s, 0.0, c.t_end);
    std::vector<double> row(static_cast<std::size_t>(nx));
    for (int i = 0; i < nx; ++i) row[static_cast<std::size_t>(i)] = s.h(i, 0);
    return row;
}

std::vector<double> smooth_errors(const SmoothCase& c, const NumericsParams& n, int n0, int levels,
                                  int ref_factor) {
    NumericsParams ref_num = n;
    ref_num.scheme = Scheme::waf;
    ref_num.limiter = Limiter::van_leer;
    const int n_ref = n0 * (1 << (levels - 1)) * ref_factor;
    const std::vector<double> ref = run_smooth(c, ref_num, n_ref);
    std::vector<double> errors;
    for (int l = 0; l < levels; ++l) {
        const int nx = n0 * (1 << l);
        const std::vector<double> h = run_smooth(c, n, nx);
        const std::vector<double> r = restrict_row(ref, n_ref / nx);
        double sum = 0.0;
        for (std::size_t i = 0; i < h.size(); ++i) sum += std::abs(h[i] - r[i]);
        errors.push_back(sum / static_cast<double>(nx));  // mean |error| (m)
    }
    return errors;
}

// ---------------------------------------------------------------- creep

CreepResult run_creep(const NumericsParams& n, EarthPressureModel model, double dx, double t_end) {
    const ScopedThreads serial(1);
    constexpr double kRadius = 10.0, kHeight = 0.4;
    const Grid g = box_grid(-14.0, 14.0, -14.0, 14.0, dx);
    const TerrainFields terrain = plane_terrain(g, 0.0, kG);
    const MaterialParams mat = material(model, 35.0, 20.0);
    State s = paraboloid_at_rest(g, kHeight, kRadius);
    const NumericsParams num = with_boundary(n, Boundary::open, kG);
    Stepper stepper(g, terrain, mat, num, effective_h_min(num, s, terrain));
    const double level = 1e-3 * kHeight;
    const int jc = g.ny / 2;  // the row just above y = 0
    const double front0 = last_x_above(s, g, jc, level);
    const double r0 = std::sqrt(6.0 * depth_moments(s, g).var_x);
    advance_to(stepper, s, 0.0, t_end);
    CreepResult r;
    r.front_shift = last_x_above(s, g, jc, level) - front0;
    r.radius_shift = std::sqrt(6.0 * depth_moments(s, g).var_x) - r0;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            if (s.h(i, j) > 0.0)
                r.max_speed = std::max(r.max_speed, std::hypot(s.hu(i, j), s.hv(i, j)) / s.h(i, j));
    return r;
}

MaterialParams material(EarthPressureModel model, double phi_deg, double delta_deg) {
    MaterialParams m;
    m.phi_deg = phi_deg;
    m.delta_deg = delta_deg;
    m.earth_pressure = model;
    return m;
}

State paraboloid_at_rest(const Grid& g, double height, double radius) {
    const auto pile = [&](double x, double y) {
        return height * std::max(0.0, 1.0 - (x * x + y * y) / (radius * radius));
    };
    return make_state(g, [&](double xa, double xb, double ya, double yb) {
        double sum = 0.0;
        constexpr int kSub = 4;
        for (int b = 0; b < kSub; ++b)
            for (int a = 0; a < kSub; ++a)
                sum += pile(xa + (a + 0.5) * (xb - xa) / kSub, ya + (b + 0.5) * (yb - ya) / kSub);
        return sum / (kSub * kSub);
    });
}

}  // namespace avalanche::analytic
