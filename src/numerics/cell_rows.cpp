#include "avalanche/numerics/cell_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "avalanche/numerics/energy_cap.hpp"
#include "avalanche/numerics/face_flux_rows.hpp"
#include "simd_clones.hpp"

namespace avalanche {

namespace {

// One sub-step of gravity and friction on the velocity (u, v) of a cell; returns
// the true speed^2 after it.
template <bool Curvature, bool Metric>
AVALANCHE_INLINE double gravity_friction(double& u, double& v, const SourceRowTerrain& t, int i,
                                         double sub, double td) {
    u += sub * t.ax[i];
    v += sub * t.ay[i];
    double load = t.gn[i];
    if constexpr (Curvature) load += t.cxx[i] * u * u + 2.0 * t.cxy[i] * u * v + t.cyy[i] * v * v;
    load = std::max(load, 0.0);  // material lifting off feels no friction
    double speed2 = u * u + v * v;
    if constexpr (Metric) {
        const double w = t.sx[i] * u + t.sy[i] * v;
        speed2 += w * w;
    }
    const double speed = std::sqrt(speed2);
    const double f = td * load * sub;
    const bool stops = speed <= f;
    const double scale = 1.0 - f / speed;  // discarded when the cell stops
    u = stops ? 0.0 : u * scale;
    v = stops ? 0.0 : v * scale;
    return stops ? 0.0 : (speed - f) * (speed - f);
}

// OneSubstep: the common m = 1 as straight-line code (GCC does not vectorise a
// loop around the sub-step loop).
template <bool Curvature, bool Metric, bool OneSubstep>
AVALANCHE_INLINE void sources_row(double* __restrict h, double* __restrict hu,
                                  double* __restrict hv, const SourceRowTerrain& t,
                                  const SourceRowParams& p, int i0, int i1) {
    const double sub = p.substep, td = p.tan_delta, g = p.gravity, budget = p.energy_budget;
    const int m = p.substeps;
    const double* __restrict elev = t.elevation;
#pragma omp simd
    for (int i = i0; i < i1; ++i) {
        const double hh = h[i];
        const bool wet = hh > 0.0;
        double u = hu[i] / hh, v = hv[i] / hh;  // discarded on dry cells
        double after2 = 0.0;                    // true speed^2 after the last sub-step
        if constexpr (OneSubstep) {
            after2 = gravity_friction<Curvature, Metric>(u, v, t, i, sub, td);
        } else {
            for (int n = 0; n < m; ++n)
                after2 = gravity_friction<Curvature, Metric>(u, v, t, i, sub, td);
        }
        // The energy cap: scale down to the cap, stop above the reachable height.
        cap_speed_selected(u, v, after2, 2.0 * (budget - g * elev[i]));
        hu[i] = wet ? hh * u : hu[i];
        hv[i] = wet ? hh * v : hv[i];
    }
}

template <bool Curvature, bool Metric>
AVALANCHE_SIMD_CLONES void sources_row_clone(double* h, double* hu, double* hv,
                                             const SourceRowTerrain& t, const SourceRowParams& p,
                                             int i0, int i1) {
    if (p.substeps == 1)
        sources_row<Curvature, Metric, true>(h, hu, hv, t, p, i0, i1);
    else
        sources_row<Curvature, Metric, false>(h, hu, hv, t, p, i0, i1);
}

AVALANCHE_SIMD_CLONES double cfl_rate_clone(const double* __restrict h, const double* __restrict hu,
                                            const double* __restrict hv,
                                            const double* __restrict px,
                                            const double* __restrict py, double kx, double ky,
                                            double dx, double dy, double h_min, int i0, int i1) {
    // The largest |u| + a of each direction, divided by the cell size once (two
    // divisions per cell fewer; 4.8 -> 3.4 ns per cell, bench_row_kernels): a correctly
    // rounded division by a positive number is monotone, so the quotient of the
    // maximum is the maximum of the quotients, bit for bit.
    double fastest_x = 0.0, fastest_y = 0.0;
#pragma omp simd reduction(max : fastest_x, fastest_y)
    for (int i = i0; i < i1; ++i) {
        const double hh = h[i];
        const double u = hu[i] / hh, v = hv[i] / hh;
        const double sx = std::abs(u) + std::sqrt(kx * px[i] * hh);
        const double sy = std::abs(v) + std::sqrt(ky * py[i] * hh);
        // max is exact, so the order of the lanes does not change the result.
        const bool skip = (hh < h_min) | (hh <= 0.0);
        fastest_x = skip ? fastest_x : std::max(fastest_x, sx);
        fastest_y = skip ? fastest_y : std::max(fastest_y, sy);
    }
    return std::max(fastest_x / dx, fastest_y / dy);
}

}  // namespace

void apply_sources_row(double* h, double* hu, double* hv, const SourceRowTerrain& t,
                       const SourceRowParams& p, int i0, int i1) noexcept {
    const bool curvature = t.cxx != nullptr, metric = t.sx != nullptr;
    if (curvature && metric)
        sources_row_clone<true, true>(h, hu, hv, t, p, i0, i1);
    else if (curvature)
        sources_row_clone<true, false>(h, hu, hv, t, p, i0, i1);
    else if (metric)
        sources_row_clone<false, true>(h, hu, hv, t, p, i0, i1);
    else
        sources_row_clone<false, false>(h, hu, hv, t, p, i0, i1);
}

double cfl_rate_row(const double* h, const double* hu, const double* hv, const double* px,
                    const double* py, double kx, double ky, double dx, double dy, double h_min,
                    int i0, int i1) noexcept {
    return cfl_rate_clone(h, hu, hv, px, py, kx, ky, dx, dy, h_min, i0, i1);
}

// ---------------------------------------------------------------- pressure row

namespace {

template <bool Isotropic, bool Metric>
AVALANCHE_INLINE void pressure_lane(const PressureRowInput& in, const PressureRowOutput& out,
                                    const PressureRowParams& p, int i, int im, int ip, int imm,
                                    int ipp) {
    const double hmin = p.h_min;
    const auto is_wet = [hmin](double hh) { return (hh >= hmin) & (hh > 0.0); };
    const auto vel = [&](double hh, double quotient) {  // the quotient q / hh
        return is_wet(hh) ? quotient : 0.0;
    };
    // A vanishing difference (at rest, or a uniformly moving block) counts as
    // extending: passive there made a mass released from rest start with the passive k
    // everywhere and grow a period-4 pattern of regimes, with errors that rose under
    // refinement (docs/verification.md, finding 2). "Vanishing" is relative (1e-12 of
    // the velocities), so round-off cannot flip it.
    const auto extends = [](double lo, double hi) {
        return hi - lo >= -1e-12 * std::max(std::abs(lo), std::abs(hi));
    };
    const double hh = in.h[i];
    double cx, cy;
    if constexpr (Isotropic) {
        cx = in.px[i];
        cy = in.py[i];
    } else {
        // Active where the flow extends (du/dx > 0), passive where it compresses
        // (Wang & Li 2017 after eq. 3). Passive takes the central difference
        // u[i+1] - u[i-1] < 0 confirmed at a second scale: both one-sided differences
        // < 0, or the difference over four cells u[i+2] - u[i-2] < 0.
        // The central difference alone does not see the cell's own velocity, while the
        // cell's pressure acts on exactly its two neighbours: a passive cell pushed
        // them apart and turned the cells two away passive, and patterns of passive
        // cells grew inside spreading flows with errors that rose under refinement
        // (similarity cap, docs/verification.md finding 2). Neither confirmation is
        // moved by that push (the cell's own velocity and u[i+/-2] stay), so a pattern
        // cannot feed itself. Either alone is not enough: the one-sided differences
        // alone make every velocity extremum active, and in a decelerating deposit,
        // where the velocities are small and noisy, the pile then spread less and less
        // as the cells got smaller (parametric chute).
        const auto active = [&](bool wide_extends, double l, double c, double r) {
            return extends(l, r) | ((extends(l, c) | extends(c, r)) & wide_extends);
        };
        const double uc = vel(hh, in.u[i]), vc = vel(hh, in.v[i]);
        // The rows two away carry momenta, not quotients: extends() of their velocities
        // multiplied out by both (positive) depths, so that no division is needed. A
        // thin or dry side counts as at rest (momentum 0 over depth 1), as vel() has it.
        const double h_ss = in.h_ss[i], h_nn = in.h_nn[i];
        const double q_ss = vel(h_ss, in.hv_ss[i]), d_ss = is_wet(h_ss) ? h_ss : 1.0;
        const double q_nn = vel(h_nn, in.hv_nn[i]), d_nn = is_wet(h_nn) ? h_nn : 1.0;
        const double lo_y = q_ss * d_nn, hi_y = q_nn * d_ss;  // v_ss, v_nn times d_ss d_nn
        const bool x_active = active(extends(vel(in.h[imm], in.u[imm]), vel(in.h[ipp], in.u[ipp])),
                                     vel(in.h[im], in.u[im]), uc, vel(in.h[ip], in.u[ip]));
        const bool y_active =
            active(extends(lo_y, hi_y), vel(in.h_s[i], in.v_s[i]), vc, vel(in.h_n[i], in.v_n[i]));
        const EarthPressureCoefficients& k = p.k;
        const double kx = x_active ? k.kx_active : k.kx_passive;
        const double ky =
            x_active ? (y_active ? k.ky_given_kx_active_active : k.ky_given_kx_active_passive)
                     : (y_active ? k.ky_given_kx_passive_active : k.ky_given_kx_passive_passive);
        cx = kx * in.px[i];
        cy = ky * in.py[i];
    }
    out.cx[i] = cx;
    out.cy[i] = cy;
    // Riemann invariants u -/+ 2a bound the velocities any Riemann fan started here can
    // produce (the invariant domain of the system); the along-surface speed plus the
    // along-surface dry-front celerity 2 sqrt(k g_n h_n) is frame-independent
    // (docs/numerics.md, step 8). Dry and thin cells bound nothing.
    const bool wet = is_wet(hh);
    const double u = in.u[i], v = in.v[i];  // hu / hh, hv / hh
    // The celerities the first-order faces take (face_flux_rows.hpp), also the bounds' a.
    const double cel_x = side_celerity(hh, cx, hmin), cel_y = side_celerity(hh, cy, hmin);
    out.ax[i] = cel_x;
    out.ay[i] = cel_y;
    const double ax = 2.0 * cel_x, ay = 2.0 * cel_y;  // used on wet cells only
    double speed2 = u * u + v * v;
    if constexpr (Metric) {
        const double w = in.sx[i] * u + in.sy[i] * v;
        speed2 += w * w;
    }
    const double shi = std::sqrt(speed2) + 2.0 * std::sqrt(p.k_max * in.gn[i] * hh * in.nt[i]);
    out.u_lo[i] = wet ? u - ax : kNoVelocityBound;
    out.u_hi[i] = wet ? u + ax : -kNoVelocityBound;
    out.v_lo[i] = wet ? v - ay : kNoVelocityBound;
    out.v_hi[i] = wet ? v + ay : -kNoVelocityBound;
    out.speed_hi[i] = wet ? shi : 0.0;
}

template <bool Isotropic, bool Metric>
AVALANCHE_SIMD_CLONES void pressure_row_clone(const PressureRowInput& in,
                                              const PressureRowOutput& out,
                                              const PressureRowParams& params, int i0, int i1, int lo,
                                              int hi) {
    // A local copy: the stores through out could alias the caller's parameters, and
    // GCC then reloads them per cell and leaves the loop scalar (it was 18 % of a step).
    const PressureRowParams p = params;
    // Central differences along the row, clamped at the padding columns lo and hi.
    int a = i0, e = i1;
    if (a < e && a == lo) {
        pressure_lane<Isotropic, Metric>(in, out, p, a, a, std::min(a + 1, hi), a,
                                         std::min(a + 2, hi));
        ++a;
    }
    if (a < e && e - 1 == hi) {
        pressure_lane<Isotropic, Metric>(in, out, p, e - 1, std::max(e - 2, lo), e - 1,
                                         std::max(e - 3, lo), e - 1);
        --e;
    }
    // The second neighbours clamped too (the first interior cell's i - 2 is lo).
    if (a < e && a == lo + 1) {
        pressure_lane<Isotropic, Metric>(in, out, p, a, a - 1, a + 1, lo, std::min(a + 2, hi));
        ++a;
    }
    if (a < e && e == hi) {
        pressure_lane<Isotropic, Metric>(in, out, p, e - 1, e - 2, e, std::max(e - 3, lo), hi);
        --e;
    }
#pragma omp simd
    for (int i = a; i < e; ++i)
        pressure_lane<Isotropic, Metric>(in, out, p, i, i - 1, i + 1, i - 2, i + 2);
}

}  // namespace

void pressure_row(const PressureRowInput& in, const PressureRowOutput& out,
                  const PressureRowParams& p, int i0, int i1, int lo, int hi) noexcept {
    const bool metric = in.sx != nullptr;
    if (p.isotropic && metric)
        pressure_row_clone<true, true>(in, out, p, i0, i1, lo, hi);
    else if (p.isotropic)
        pressure_row_clone<true, false>(in, out, p, i0, i1, lo, hi);
    else if (metric)
        pressure_row_clone<false, true>(in, out, p, i0, i1, lo, hi);
    else
        pressure_row_clone<false, false>(in, out, p, i0, i1, lo, hi);
}

// ---------------------------------------------------------------- velocity quotients

namespace {
AVALANCHE_SIMD_CLONES void state_velocity_clone(const double* __restrict h,
                                                const double* __restrict hu,
                                                const double* __restrict hv, double* __restrict u,
                                                double* __restrict v, int i0, int i1) {
#pragma omp simd
    for (int i = i0; i < i1; ++i) {
        u[i] = hu[i] / h[i];
        v[i] = hv[i] / h[i];
    }
}
}  // namespace

void state_velocity_row(const double* h, const double* hu, const double* hv, double* u, double* v,
                        int i0, int i1) noexcept {
    state_velocity_clone(h, hu, hv, u, v, i0, i1);
}

}  // namespace avalanche
