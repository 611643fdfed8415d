#include "avalanche/numerics/cell_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "avalanche/numerics/energy_cap.hpp"
#include "avalanche/numerics/face_flux_rows.hpp"
#include "avalanche/physics/dem_coefficients.hpp"
#include "simd_clones.hpp"

namespace avalanche {

namespace {

// One sub-step of gravity and friction on the velocity (u, v) of a cell; returns
// the true speed^2 after it.
template <bool Curvature, bool Metric>
AVALANCHE_INLINE double gravity_friction(double& u, double& v, const SourceRowTerrain& t, int i,
                                         double sub, double td) {
    double ax, ay, load;
    if constexpr (Metric) {
        // The DEM frame's coefficients from the slopes, not read (dem_coefficients.hpp).
        const DemCoefficients c = dem_coefficients(t.sx[i], t.sy[i], t.slope_gravity);
        ax = c.ax;
        ay = c.ay;
        load = c.gn;
    } else {
        ax = t.ax[i];
        ay = t.ay[i];
        load = t.gn[i];
    }
    u += sub * ax;
    v += sub * ay;
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
        const double inv = 1.0 / hh;              // one division for both quotients
        double u = hu[i] * inv, v = hv[i] * inv;  // discarded on dry cells
        double after2 = 0.0;                      // true speed^2 after the last sub-step
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

template <bool Metric>
AVALANCHE_SIMD_CLONES double cfl_rate_clone(const double* __restrict h, const double* __restrict hu,
                                            const double* __restrict hv, const CflRowTerrain& t,
                                            double kx, double ky, double dx, double dy,
                                            double h_min, int i0, int i1) {
    // The largest |u| + a of each direction, divided by the cell size once (two
    // divisions per cell fewer; 4.8 -> 3.4 ns per cell, bench_row_kernels): a correctly
    // rounded division by a positive number is monotone, so the quotient of the
    // maximum is the maximum of the quotients, bit for bit.
    const double* __restrict px = t.px;
    const double* __restrict py = t.py;
    const double* __restrict sx = t.sx;
    const double* __restrict sy = t.sy;
    const double g = t.slope_gravity;
    double fastest_x = 0.0, fastest_y = 0.0;
#pragma omp simd reduction(max : fastest_x, fastest_y)
    for (int i = i0; i < i1; ++i) {
        const double hh = h[i];
        const double inv = 1.0 / hh;
        const double u = hu[i] * inv, v = hv[i] * inv;
        double pxi, pyi;
        if constexpr (Metric) {
            // The DEM frame's coefficients from the slopes (dem_coefficients.hpp).
            const DemCoefficients c = dem_coefficients(sx[i], sy[i], g);
            pxi = c.px;
            pyi = c.py;
        } else {
            pxi = px[i];
            pyi = py[i];
        }
        const double fx = std::abs(u) + std::sqrt(kx * pxi * hh);
        const double fy = std::abs(v) + std::sqrt(ky * pyi * hh);
        // max is exact, so the order of the lanes does not change the result.
        const bool skip = (hh < h_min) | (hh <= 0.0);
        fastest_x = skip ? fastest_x : std::max(fastest_x, fx);
        fastest_y = skip ? fastest_y : std::max(fastest_y, fy);
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

double cfl_rate_row(const double* h, const double* hu, const double* hv, const CflRowTerrain& t,
                    double kx, double ky, double dx, double dy, double h_min, int i0,
                    int i1) noexcept {
    return t.sx != nullptr ? cfl_rate_clone<true>(h, hu, hv, t, kx, ky, dx, dy, h_min, i0, i1)
                           : cfl_rate_clone<false>(h, hu, hv, t, kx, ky, dx, dy, h_min, i0, i1);
}

// ---------------------------------------------------------------- state scan

namespace {

constexpr int kScanLanes = 8;  // fixed, not the vector width: the sum's bits do not depend on it

// Whether the time loop's scan rejects a cell: a non-finite value or a negative depth.
AVALANCHE_INLINE bool bad_cell(double h, double hu, double hv) {
    constexpr double kMax = std::numeric_limits<double>::max();
    // Ordered comparisons: false for NaN, so a NaN anywhere makes the cell bad. Bitwise
    // '&' on purpose (no branches in the vector loop); the magnitudes first, so that no
    // operand is a call (clang's -Wbitwise-instead-of-logical).
    const double abs_hu = std::abs(hu), abs_hv = std::abs(hv);
    const bool ok = (h >= 0.0) & (h <= kMax) & (abs_hu <= kMax) & (abs_hv <= kMax);
    return !ok;
}

AVALANCHE_SIMD_CLONES StateRowScan scan_clone(const double* __restrict h,
                                              const double* __restrict hu,
                                              const double* __restrict hv, int i0, int i1) {
    double energy[kScanLanes] = {}, bad[kScanLanes] = {}, moving[kScanLanes] = {};
    const auto cell = [&](int l, int i) __attribute__((always_inline)) {
        const double hh = h[i], qx = hu[i], qy = hv[i];
        const double e = (qx * qx + qy * qy) / hh;  // 0 / 0 on a dry cell, discarded
        energy[l] += hh > 0.0 ? e : 0.0;
        bad[l] += bad_cell(hh, qx, qy) ? 1.0 : 0.0;
        moving[l] += ((qx != 0.0) | (qy != 0.0)) ? 1.0 : 0.0;
    };
    const int whole = i0 + (i1 - i0) / kScanLanes * kScanLanes;
    for (int a = i0; a < whole; a += kScanLanes) {
#pragma omp simd
        for (int l = 0; l < kScanLanes; ++l) cell(l, a + l);
    }
    for (int i = whole; i < i1; ++i) cell(i - whole, i);
    StateRowScan r;
    double any_bad = 0.0, any_moving = 0.0;
    for (int l = 0; l < kScanLanes; ++l) {
        r.twice_kinetic += energy[l];
        any_bad += bad[l];
        any_moving += moving[l];
    }
    r.moving = any_moving != 0.0;
    if (any_bad != 0.0)
        for (int i = i0; i < i1; ++i)
            if (bad_cell(h[i], hu[i], hv[i])) {
                r.first_bad = i;
                break;
            }
    return r;
}

}  // namespace

StateRowScan state_scan_row(const double* h, const double* hu, const double* hv, int i0,
                            int i1) noexcept {
    return scan_clone(h, hu, hv, i0, i1);
}

// ---------------------------------------------------------------- pressure row

namespace {

template <bool Isotropic, bool Metric>
AVALANCHE_INLINE void pressure_lane(const PressureRowInput& in, const PressureRowOutput& out,
                                    const PressureRowParams& p, int i) {
    const double hmin = p.h_min;
    const double hh = in.h[i];
    double px, py, gn_nt;  // gn_nt: the load on a bed-normal depth, g_n times its factor
    if constexpr (Metric) {
        // The DEM frame's coefficients from the slopes, not read (dem_coefficients.hpp).
        const DemCoefficients c = dem_coefficients(in.sx[i], in.sy[i], in.slope_gravity);
        px = c.px;
        py = c.py;
        gn_nt = c.gn_nt;
    } else {
        px = in.px[i];
        py = in.py[i];
        gn_nt = in.gn[i] * in.nt[i];
    }
    double cx, cy;
    if constexpr (Isotropic) {
        cx = px;
        cy = py;
    } else {
        // The cell's regime (regime_row): active where the flow extends, passive where
        // it compresses (Wang & Li 2017 after eq. 3).
        const bool x_active = (in.regime[i] & kRegimeXActive) != 0;
        const bool y_active = (in.regime[i] & kRegimeYActive) != 0;
        const EarthPressureCoefficients& k = p.k;
        const double kx = x_active ? k.kx_active : k.kx_passive;
        const double ky =
            x_active ? (y_active ? k.ky_given_kx_active_active : k.ky_given_kx_active_passive)
                     : (y_active ? k.ky_given_kx_passive_active : k.ky_given_kx_passive_passive);
        cx = kx * px;
        cy = ky * py;
    }
    out.cx[i] = cx;
    out.cy[i] = cy;
    // Riemann invariants u -/+ 2a bound the velocities any Riemann fan started here can
    // produce (the invariant domain of the system); the along-surface speed plus the
    // along-surface dry-front celerity 2 sqrt(k g_n h_n) is frame-independent
    // (docs/numerics.md, step 8). Dry and thin cells bound nothing.
    const bool wet = is_wet(hh, hmin);
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
    const double shi = std::sqrt(speed2) + 2.0 * std::sqrt(p.k_max * gn_nt * hh);
    out.u_lo[i] = wet ? u - ax : kNoVelocityBound;
    out.u_hi[i] = wet ? u + ax : -kNoVelocityBound;
    out.v_lo[i] = wet ? v - ay : kNoVelocityBound;
    out.v_hi[i] = wet ? v + ay : -kNoVelocityBound;
    out.speed_hi[i] = wet ? shi : 0.0;
}

template <bool Isotropic, bool Metric>
AVALANCHE_SIMD_CLONES void pressure_row_clone(const PressureRowInput& in,
                                              const PressureRowOutput& out,
                                              const PressureRowParams& params, int i0, int i1) {
    // A local copy: the stores through out could alias the caller's parameters, and
    // GCC then reloads them per cell and leaves the loop scalar (it was 18 % of a step).
    const PressureRowParams p = params;
#pragma omp simd
    for (int i = i0; i < i1; ++i) pressure_lane<Isotropic, Metric>(in, out, p, i);
}

}  // namespace

void pressure_row(const PressureRowInput& in, const PressureRowOutput& out,
                  const PressureRowParams& p, int i0, int i1) noexcept {
    const bool metric = in.sx != nullptr;
    if (p.isotropic && metric)
        pressure_row_clone<true, true>(in, out, p, i0, i1);
    else if (p.isotropic)
        pressure_row_clone<true, false>(in, out, p, i0, i1);
    else if (metric)
        pressure_row_clone<false, true>(in, out, p, i0, i1);
    else
        pressure_row_clone<false, false>(in, out, p, i0, i1);
}

// ---------------------------------------------------------------- velocity quotients

namespace {
AVALANCHE_SIMD_CLONES void state_velocity_clone(const double* __restrict h,
                                                const double* __restrict hu,
                                                const double* __restrict hv, double* __restrict u,
                                                double* __restrict v, int i0, int i1) {
#pragma omp simd
    for (int i = i0; i < i1; ++i) {
        const VelocityQuotients q = velocity_quotients(h[i], hu[i], hv[i]);
        u[i] = q.u;
        v[i] = q.v;
    }
}
}  // namespace

void state_velocity_row(const double* h, const double* hu, const double* hv, double* u, double* v,
                        int i0, int i1) noexcept {
    state_velocity_clone(h, hu, hv, u, v, i0, i1);
}

}  // namespace avalanche
