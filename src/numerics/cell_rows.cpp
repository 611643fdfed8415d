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
        const double inv = 1.0 / hh;
        const double u = hu[i] * inv, v = hv[i] * inv;
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

// ---------------------------------------------------------------- state scan

namespace {

constexpr int kScanLanes = 8;  // fixed, not the vector width: the sum's bits do not depend on it

// Whether the time loop's scan rejects a cell: a non-finite value or a negative depth.
AVALANCHE_INLINE bool bad_cell(double h, double hu, double hv) {
    constexpr double kMax = std::numeric_limits<double>::max();
    // Ordered comparisons: false for NaN, so a NaN anywhere makes the cell bad.
    const bool ok = (h >= 0.0) & (h <= kMax) & (std::abs(hu) <= kMax) & (std::abs(hv) <= kMax);
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
        moving[l] += (qx != 0.0) | (qy != 0.0) ? 1.0 : 0.0;
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

// ---------------------------------------------------------------- regime row

namespace {

// The regime of cell i from its previous regime: x from the cells im, ip (one away)
// and imm, ipp (two away) of the row, y from the rows s, n, ss, nn. A velocity is a
// (momentum, depth) pair, a thin or dry cell's (momentum 0 over depth 1; a difference
// with one extends, whatever the velocities, see extends below), and
// differences of velocities are compared multiplied out by both (positive) depths, so
// that no division is needed. Metric: the DEM frame, whose velocities are horizontal;
// the rest test takes the along-surface component u sqrt(1 + s_x^2), v sqrt(1 + s_y^2).
template <bool Metric, bool Both>
AVALANCHE_INLINE void regime_lane(const RegimeRowInput& in, RegimeFlags* regime, double hmin,
                                  double rest2, int i, int im, int ip, int imm, int ipp) {
    // Whether the velocity does not fall from a to b: b - a >= 0 up to a relative
    // 1e-12, so that round-off cannot make a vanishing difference (at rest, or a
    // uniformly moving block) compress. A vanishing difference extends: taken for
    // compressing, it made a mass released from rest start passive everywhere and grow a
    // period-4 pattern of regimes, with errors that rose under refinement
    // (docs/verification.md, finding 2). Two velocities both within the rest speed
    // (rest2 its square) vanish too: in a deposit the splitting leaves velocities of the
    // order of a step's friction impulse that mean nothing, and regimes decided by them
    // set neighbouring cells' pressures k_pass / k_act apart, a push the friction could
    // not hold: with one advection per step at Courant 0.4 the parametric chute's deposit
    // on 0.125 m cells kept moving, cell against cell, at up to 0.4 m/s for 40 s.
    // A thin or dry cell has no velocity of its own, and a difference with one extends
    // too: the edge of a flow spreading into dry ground is active. (Taken for a cell at
    // rest, the dry ground made the last wet cell of a spreading front compress, turned
    // it passive, and on cells of 0.0125 m the cap released from rest grew a period-2
    // oscillation from its front that ran through the body: docs/verification.md,
    // finding 2.)
    // ra, rb: 1 where the cell is within the rest speed, else 0; wa, wb: 1 where it is
    // wet, 0 where thin or dry. (Products, not selections, and the lambdas forced inline:
    // else GCC 12 left the loop scalar, at 25-65 ns per cell.)
    const auto extends = [](double qa, double da, double ra, double wa, double qb, double db,
                            double rb, double wb) __attribute__((always_inline)) {
        const double lo = qa * db, hi = qb * da;  // a and b times both depths
        const double rises = hi - lo >= -1e-12 * std::max(std::abs(lo), std::abs(hi)) ? 1.0 : 0.0;
        return 1.0 - (1.0 - std::max(rises, ra * rb)) * (wa * wb);
    };
    // 1 where the along-surface component q/d sqrt(m) is within the rest speed (m = 1 + s^2,
    // 1 in bed-fitted frames).
    const auto rest_of = [rest2](double q, double d, double m) {
        return q * q * m <= rest2 * (d * d) ? 1.0 : 0.0;
    };
    // Passive where the central difference compresses and a second scale confirms it:
    // both one-sided differences, or the difference over four cells. The central
    // difference alone does not see the cell's own velocity, while the cell's pressure
    // acts on exactly its two neighbours: a passive cell pushed them apart and turned
    // the cells two away passive, and patterns of passive cells grew inside spreading
    // flows (similarity cap, docs/verification.md finding 2). Neither confirmation is
    // moved by that push. Active where the central difference extends. A central
    // compression that nothing confirms decides nothing: the cell keeps its regime.
    // (Taking it for active there, as the rule did until 2026-12-02, let a decelerating
    // deposit, whose small velocities make such cells common, spread less and less as
    // the cells got smaller; taking it for passive grew the patterns again.)
    // Both: the first-order scheme's rule (RegimeRowInput::confirm_at_both_scales), which
    // needs both confirmations, the one-sided differences and the four-cell difference.
    // Its profiles are smeared over more cells, and at a smeared edge the velocity
    // wiggles over a few cells, which one of the two scales takes for a compression:
    // Godunov's cap released from rest failed on 0.0125 m cells (E1 0.24) with either
    // confirmation, and converges at first order with both. WAF keeps either: with both,
    // the compressions of its decelerating deposits that one scale confirms were left
    // active and its fine deposits came out shorter and steeper (docs/verification.md,
    // finding 2).
    const auto q_of = [hmin](double hh, double q) { return is_wet(hh, hmin) ? q : 0.0; };
    const auto d_of = [hmin](double hh) { return is_wet(hh, hmin) ? hh : 1.0; };
    const auto m_of = [](const double* slope, int k) {
        if constexpr (Metric) return 1.0 + slope[k] * slope[k];
        return 1.0;
    };
    // The new regime (1 active, 0 passive, as doubles like everything else in the loop)
    // from the previous one and the cells ll, l, c, r, rr of a direction: depths h,
    // momenta q and metric factors m.
    struct Cell {
        double h, q, m;
    };
    const auto w_of = [hmin](double hh) { return is_wet(hh, hmin) ? 1.0 : 0.0; };
    const auto next = [&](double was_active, Cell ll, Cell l, Cell c, Cell r,
                          Cell rr) __attribute__((always_inline)) {
        const double Qll = q_of(ll.h, ll.q), Dll = d_of(ll.h), Ql = q_of(l.h, l.q), Dl = d_of(l.h);
        const double Qc = q_of(c.h, c.q), Dc = d_of(c.h), Qr = q_of(r.h, r.q), Dr = d_of(r.h);
        const double Qrr = q_of(rr.h, rr.q), Drr = d_of(rr.h);
        const double Rll = rest_of(Qll, Dll, ll.m), Rl = rest_of(Ql, Dl, l.m);
        const double Rc = rest_of(Qc, Dc, c.m), Rr = rest_of(Qr, Dr, r.m);
        const double Rrr = rest_of(Qrr, Drr, rr.m);
        const double Wll = w_of(ll.h), Wl = w_of(l.h), Wc = w_of(c.h), Wr = w_of(r.h);
        const double Wrr = w_of(rr.h);
        // 1 or 0 each.
        const double central = extends(Ql, Dl, Rl, Wl, Qr, Dr, Rr, Wr);
        const double one_sided = (1.0 - extends(Ql, Dl, Rl, Wl, Qc, Dc, Rc, Wc)) *
                                 (1.0 - extends(Qc, Dc, Rc, Wc, Qr, Dr, Rr, Wr));
        const double four_cells = 1.0 - extends(Qll, Dll, Rll, Wll, Qrr, Drr, Rrr, Wrr);
        const double confirmed = Both ? one_sided * four_cells : std::max(one_sided, four_cells);
        return std::max(central, (1.0 - confirmed) * was_active);
    };
    const double hh = in.h[i];
    const double was = static_cast<double>(regime[i]);
    const double was_y = was >= kRegimeYActive ? 1.0 : 0.0, was_x = was - kRegimeYActive * was_y;
    const double x_active =
        next(was_x, {in.h[imm], in.hu[imm], m_of(in.sx, imm)},
             {in.h[im], in.hu[im], m_of(in.sx, im)}, {hh, in.hu[i], m_of(in.sx, i)},
             {in.h[ip], in.hu[ip], m_of(in.sx, ip)}, {in.h[ipp], in.hu[ipp], m_of(in.sx, ipp)});
    const double y_active = next(
        was_y, {in.h_ss[i], in.hv_ss[i], m_of(in.sy_ss, i)},
        {in.h_s[i], in.hv_s[i], m_of(in.sy_s, i)}, {hh, in.hv[i], m_of(in.sy, i)},
        {in.h_n[i], in.hv_n[i], m_of(in.sy_n, i)}, {in.h_nn[i], in.hv_nn[i], m_of(in.sy_nn, i)});
    const double now = kRegimeXActive * x_active + kRegimeYActive * y_active;
    regime[i] = static_cast<RegimeFlags>(is_wet(hh, hmin) ? now : double{kRegimeAtStart});
}

// Without tree-PRE: GCC 12 otherwise carries loads of one cell's neighbours over to the
// next cell, a loop-carried value its vectoriser rejects ("unknown def-use cycle"), and
// the loop stayed scalar: 10.6-29 ns per cell against 3.5 (bench_row_kernels).
template <bool Metric, bool Both>
__attribute__((optimize("no-tree-pre"))) AVALANCHE_SIMD_CLONES void regime_row_clone(
    const RegimeRowInput& input, RegimeFlags* regime, double h_min, double rest_speed, int i0,
    int i1, int lo, int hi) {
    // A local copy, so that GCC need not prove that the stores through regime leave the
    // caller's row pointers alone.
    const RegimeRowInput in = input;
    const double rest2 = rest_speed * rest_speed;
    // The cells whose differences need no clamp (vectorised), then those within two
    // columns of the padding columns lo and hi, clamped.
    const int a = std::min(std::max(i0, lo + 2), i1), e = std::max(std::min(i1, hi - 1), a);
#pragma omp simd
    for (int i = a; i < e; ++i)
        regime_lane<Metric, Both>(in, regime, h_min, rest2, i, i - 1, i + 1, i - 2, i + 2);
    const auto clamped = [&](int i) {
        regime_lane<Metric, Both>(in, regime, h_min, rest2, i, std::max(i - 1, lo),
                                  std::min(i + 1, hi), std::max(i - 2, lo), std::min(i + 2, hi));
    };
    for (int i = i0; i < a; ++i) clamped(i);
    for (int i = e; i < i1; ++i) clamped(i);
}

}  // namespace

void regime_row(const RegimeRowInput& in, RegimeFlags* regime, double h_min, double rest_speed,
                int i0, int i1, int lo, int hi) noexcept {
    const bool metric = in.sx != nullptr;
    if (in.confirm_at_both_scales) {
        if (metric)
            regime_row_clone<true, true>(in, regime, h_min, rest_speed, i0, i1, lo, hi);
        else
            regime_row_clone<false, true>(in, regime, h_min, rest_speed, i0, i1, lo, hi);
    } else if (metric) {
        regime_row_clone<true, false>(in, regime, h_min, rest_speed, i0, i1, lo, hi);
    } else {
        regime_row_clone<false, false>(in, regime, h_min, rest_speed, i0, i1, lo, hi);
    }
}

// ---------------------------------------------------------------- pressure row

namespace {

template <bool Isotropic, bool Metric>
AVALANCHE_INLINE void pressure_lane(const PressureRowInput& in, const PressureRowOutput& out,
                                    const PressureRowParams& p, int i) {
    const double hmin = p.h_min;
    const double hh = in.h[i];
    double cx, cy;
    if constexpr (Isotropic) {
        cx = in.px[i];
        cy = in.py[i];
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
        cx = kx * in.px[i];
        cy = ky * in.py[i];
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
        const double inv = 1.0 / h[i];  // one division for both quotients
        u[i] = hu[i] * inv;
        v[i] = hv[i] * inv;
    }
}
}  // namespace

void state_velocity_row(const double* h, const double* hu, const double* hv, double* u, double* v,
                        int i0, int i1) noexcept {
    state_velocity_clone(h, hu, hv, u, v, i0, i1);
}

}  // namespace avalanche
