#include "avalanche/numerics/update_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/energy_cap.hpp"
#include "simd_clones.hpp"

namespace avalanche {

namespace {

constexpr double kRedo = std::numeric_limits<double>::quiet_NaN();

// std::max(x, 0.0) on a value: std::max on an array element returns a reference to
// one of its arguments, a conditional load GCC does not vectorise.
AVALANCHE_INLINE double max0(double x) { return x < 0.0 ? 0.0 : x; }

AVALANCHE_SIMD_CLONES void donor_factor_clone(const FaceFluxRows& f, const double* __restrict h,
                                              double rx, double ry, double h_min, std::ptrdiff_t st,
                                              double* __restrict factor, int i0, int i1) {
    const double* __restrict fx = f.fx_h;
    const double* __restrict fy = f.fy_h;
    // Few cells would be emptied (thin cells at a front): the vector loop marks them
    // with a NaN and a scalar pass divides for them alone.
    const auto outgoing = [&](int i) {
        return rx * (max0(fx[i + 1]) + max0(-fx[i])) + ry * (max0(fy[i + st]) + max0(-fy[i]));
    };
    double n_emptied = 0.0;
#pragma omp simd reduction(+ : n_emptied)
    for (int i = i0; i < i1; ++i) {
        const double hk = h[i];
        const double out = outgoing(i);
        const bool emptied = !(hk < h_min) & (out > hk);
        factor[i] = hk < h_min ? 0.0 : (emptied ? kRedo : 1.0);
        n_emptied += emptied ? 1.0 : 0.0;
    }
    if (n_emptied == 0.0) return;
    for (int i = i0; i < i1; ++i)
        if (std::isnan(factor[i])) factor[i] = h[i] / outgoing(i);
}

// The scalar finish of one cell update_clone marked (its depth kept negated, its momentum
// before the bounds): the velocity clamp to the 3 x 3 block's bounds, the block's speed
// bound and the energy cap, the definition the vector loop follows.
void update_cell(const UpdateRowInput& in, const UpdateRowParams& p, bool metric, double* h_new,
                 double* hu_new, double* hv_new, int i) {
    // The depth and momentum update_clone computed, kept for the marked cell (the
    // state may have been overwritten: the update works in place).
    const double hn = -h_new[i];
    const double qu = hu_new[i], qv = hv_new[i];
    const std::ptrdiff_t st = p.stride;
    h_new[i] = hn;
    // Min / max over the 3 x 3 block around i (exact, so the order does not matter).
    const auto min9 = [st, i](const double* b) {
        double m = kNoVelocityBound;
        for (std::ptrdiff_t r = i - st; r <= i + st; r += st)
            m = std::min({m, b[r - 1], b[r], b[r + 1]});
        return m;
    };
    const auto max9 = [st, i](const double* b, double init) {
        double m = init;
        for (std::ptrdiff_t r = i - st; r <= i + st; r += st)
            m = std::max({m, b[r - 1], b[r], b[r + 1]});
        return m;
    };
    const double inv = 1.0 / hn;  // as update_row's marking pass
    double u = qu * inv, v = qv * inv;
    if (!(in.u_lo[i] <= u && u <= in.u_hi[i] && in.v_lo[i] <= v && v <= in.v_hi[i])) {
        const double ulo = min9(in.u_lo), uhi = max9(in.u_hi, -kNoVelocityBound);
        if (ulo > uhi) {  // no wet cell around: nothing can have moved it
            hu_new[i] = hv_new[i] = 0.0;
            return;
        }
        const double vlo = min9(in.v_lo), vhi = max9(in.v_hi, -kNoVelocityBound);
        if (u < ulo || u > uhi) u = std::clamp(u, ulo, uhi);
        if (v < vlo || v > vhi) v = std::clamp(v, vlo, vhi);
    }
    double speed2 = u * u + v * v;
    if (metric) {
        const double w = in.sx[i] * u + in.sy[i] * v;
        speed2 += w * w;
    }
    if (speed2 > in.speed_hi[i] * in.speed_hi[i]) {  // again the own bound first
        const double speed_bound = max9(in.speed_hi, 0.0);
        if (speed2 > speed_bound * speed_bound) {
            const double scale = speed_bound / std::sqrt(speed2);
            u *= scale;
            v *= scale;
            speed2 = speed_bound * speed_bound;
        }
    }
    cap_speed(u, v, speed2, 2.0 * (p.energy_budget - p.gravity * in.elevation[i]));
    hu_new[i] = hn * u;
    hv_new[i] = hn * v;
}

// The common case of every cell (the velocity within the cell's own bounds and under
// the energy cap) with selections; the other cells are marked for update_cell: their
// depth is stored negated (a NaN depth stays NaN) and their momentum as it was before
// the bounds. Returns the number of cells marked, so that the caller can skip its
// search for them when there is none (the common case).
// The update may be in place (h_new == in.h, ...): each cell reads only its own state
// before it writes it, so these pointers are not restrict; omp simd vectorises anyway.
template <bool Metric>
AVALANCHE_SIMD_CLONES double update_clone(const UpdateRowInput& in, const UpdateRowParams& p,
                                          double* h_new, double* hu_new, double* hv_new, int i0,
                                          int i1) {
    const std::ptrdiff_t st = p.stride;
    const double rx = p.rx, ry = p.ry, budget = p.energy_budget, g = p.gravity;
    const double h_thin = p.h_thin;
    const double* __restrict fxh = in.f.fx_h;
    const double* __restrict fxu = in.f.fx_hu;
    const double* __restrict fxv = in.f.fx_hv;
    const double* __restrict fyh = in.f.fy_h;
    const double* __restrict fyu = in.f.fy_hu;
    const double* __restrict fyv = in.f.fy_hv;
    const double* __restrict factor = in.factor;
    const double* h = in.h;
    const double* hu = in.hu;
    const double* hv = in.hv;
    const double* __restrict ulo = in.u_lo;
    const double* __restrict uhi = in.u_hi;
    const double* __restrict vlo = in.v_lo;
    const double* __restrict vhi = in.v_hi;
    const double* __restrict shi = in.speed_hi;
    const double* __restrict elev = in.elevation;
    const double* __restrict sx = in.sx;
    const double* __restrict sy = in.sy;
#pragma omp simd
    for (int i = i0; i < i1; ++i) {
        // The five factors are loaded before they are selected: a selection between
        // two addresses would be a gather, which keeps the loop scalar.
        const double f_w = factor[i - 1], f_c = factor[i], f_e = factor[i + 1];
        const double f_s = factor[i - st], f_n = factor[i + st];
        const double fw = donor_factor_of(fxh[i], f_w, f_c);
        const double fe = donor_factor_of(fxh[i + 1], f_c, f_e);
        const double fs = donor_factor_of(fyh[i], f_s, f_c);
        const double fn = donor_factor_of(fyh[i + st], f_c, f_n);
        double hn =
            h[i] - rx * (fxh[i + 1] * fe - fxh[i] * fw) - ry * (fyh[i + st] * fn - fyh[i] * fs);
        hn = hn < 0.0 ? 0.0 : hn;
        const double qu =
            hu[i] - (rx * (fxu[i + 1] * fe - fxu[i] * fw) + ry * (fyu[i + st] * fn - fyu[i] * fs));
        const double qv =
            hv[i] - (rx * (fxv[i + 1] * fe - fxv[i] * fw) + ry * (fyv[i + st] * fn - fyv[i] * fs));
        h_new[i] = hn;
        hu_new[i] = qu;  // momentum before the velocity bounds, finished below
        hv_new[i] = qv;
    }
    // The velocity bounds as a second pass over the row (one loop with both parts is
    // not vectorised by GCC 12).
    double marked = 0.0;
#pragma omp simd reduction(+ : marked)
    for (int i = i0; i < i1; ++i) {
        const double hn = h_new[i];
        // An empty cell, or one the thin-layer rule gives its velocity after the
        // advection: zero momentum (at the margins of a real flow most of the cells
        // outside their own bounds are such films: their bounds were dry).
        const bool empty = (hn <= 0.0) | (hn < h_thin);
        const double inv = 1.0 / hn;
        const double qu = hu_new[i], qv = hv_new[i];
        const double u = qu * inv, v = qv * inv;  // discarded when empty
        // Within the cell's own bounds (a NaN velocity is not): written as a product of
        // selections, as a chain of && or & is not vectorised by GCC 12.
        const double own = (ulo[i] <= u ? 1.0 : 0.0) * (u <= uhi[i] ? 1.0 : 0.0) *
                           (vlo[i] <= v ? 1.0 : 0.0) * (v <= vhi[i] ? 1.0 : 0.0);
        double speed2 = u * u + v * v;
        if constexpr (Metric) {
            const double w = sx[i] * u + sy[i] * v;
            speed2 += w * w;
        }
        const double slow = speed2 > shi[i] * shi[i] ? 0.0 : 1.0;
        // The energy cap acts on few cells; its quotient and root are left to
        // update_cell.
        const double uncapped = speed2 <= 2.0 * (budget - g * elev[i]) ? 1.0 : 0.0;
        // A cell outside its own bounds or over the cap is marked (a NaN the update
        // produces is recomputed as well).
        const bool redo = empty ? false : own * slow * uncapped == 0.0;
        h_new[i] = redo ? -hn : hn;
        hu_new[i] = redo ? qu : (empty ? 0.0 : hn * u);
        hv_new[i] = redo ? qv : (empty ? 0.0 : hn * v);
        marked += redo ? 1.0 : 0.0;
    }
    return marked;
}

// A cell update_clone marked: its depth stored negated, or NaN.
AVALANCHE_INLINE bool is_marked(double h_stored) { return !(h_stored >= 0.0); }

}  // namespace

void donor_factor_row(const FaceFluxRows& f, const double* h, double rx, double ry, double h_min,
                      std::ptrdiff_t stride, double* factor, int i0, int i1) noexcept {
    donor_factor_clone(f, h, rx, ry, h_min, stride, factor, i0, i1);
}

void update_row(const UpdateRowInput& in, const UpdateRowParams& p, double* h_new, double* hu_new,
                double* hv_new, int i0, int i1) noexcept {
    const bool metric = in.sx != nullptr;
    const double marked = metric ? update_clone<true>(in, p, h_new, hu_new, hv_new, i0, i1)
                                 : update_clone<false>(in, p, h_new, hu_new, hv_new, i0, i1);
    if (marked == 0.0) return;
    for (int i = i0; i < i1; ++i)
        if (is_marked(h_new[i])) update_cell(in, p, metric, h_new, hu_new, hv_new, i);
}

}  // namespace avalanche
