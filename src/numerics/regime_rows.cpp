#include "avalanche/numerics/regime_rows.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/face_flux_rows.hpp"
#include "simd_clones.hpp"

namespace avalanche {

namespace {

// Whether the velocity does not fall from cell a to cell b, 1.0 or 0.0 ("extends"). A
// velocity is a (momentum q, depth h) pair, and b - a >= 0 is compared multiplied out
// by both (positive) depths, so that no division is needed, up to a relative 1e-12, so
// that round-off cannot make a vanishing difference (at rest, or a uniformly moving
// block) compress. A vanishing difference extends: taken for compressing, it made a
// mass released from rest start passive everywhere and grow a period-4 pattern of
// regimes, with errors that rose under refinement (docs/verification.md, finding 2).
// Two velocities both within the rest speed (still: regime_terms_row) vanish too: in a
// deposit the splitting leaves velocities of the order of a step's friction impulse
// that mean nothing, and regimes decided by them set neighbouring cells' pressures
// k_pass / k_act apart, a push the friction could not hold: with one advection per step
// at Courant 0.4 the parametric chute's deposit on 0.125 m cells kept moving, cell
// against cell, at up to 0.4 m/s for 40 s.
// A thin or dry cell (wet 0) has no velocity of its own, and a difference with one
// extends, whatever its stored values: the edge of a flow spreading into dry ground is
// active. (Taken for a cell at rest, the dry ground made the last wet cell of a
// spreading front compress, turned it passive, and on cells of 0.0125 m the cap
// released from rest grew a period-2 oscillation from its front that ran through the
// body: docs/verification.md, finding 2.) The products of 0/1 doubles are never NaN, so
// wa wb = 0 gives 1 whatever the depths and momenta of a dry cell make of the rest.
// (Products, not selections, and forced inline: else GCC 12 left the loops scalar, at
// 25-65 ns per cell.)
AVALANCHE_INLINE double extends(double qa, double ha, double sa, double wa, double qb, double hb,
                                double sb, double wb) {
    const double lo = qa * hb, hi = qb * ha;  // a and b times both depths
    const double rises = hi - lo >= -1e-12 * std::max(std::abs(lo), std::abs(hi)) ? 1.0 : 0.0;
    return 1.0 - (1.0 - std::max(rises, sa * sb)) * (wa * wb);
}

// The new regime of a direction (1 active, 0 passive, as doubles like everything else
// in the loops) from the previous one and the extends of the central difference, the
// two one-sided ones and the one over four cells.
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
template <bool Both>
AVALANCHE_INLINE double next_regime(double was_active, double central, double left, double right,
                                    double four) {
    const double one_sided = (1.0 - left) * (1.0 - right);
    const double four_cells = 1.0 - four;
    const double confirmed = Both ? one_sided * four_cells : std::max(one_sided, four_cells);
    return std::max(central, (1.0 - confirmed) * was_active);
}

// ---------------------------------------------------------------- per cell, per row

// With Velocity, also the velocity quotients u, v, with state_velocity_row's
// expression (velocity_quotients): the state rows are read once for both (case (a): the
// quotients' own pass read h, hu, hv from memory and the terms read them again).
template <bool Metric, bool Velocity>
AVALANCHE_SIMD_CLONES void terms_clone(const double* __restrict h, const double* __restrict hu,
                                       const double* __restrict hv, const double* __restrict sx,
                                       const double* __restrict sy, double h_min, double rest2,
                                       double* __restrict wet, double* __restrict still_x,
                                       double* __restrict still_y, double* __restrict u,
                                       double* __restrict v, int i0, int i1) {
#pragma omp simd
    for (int i = i0; i < i1; ++i) {
        const double d = h[i];
        const double w = is_wet(d, h_min) ? 1.0 : 0.0;
        // 1 + s^2: the along-surface component of a horizontal velocity component, squared,
        // over the component squared (1 in bed-fitted frames).
        const double mx = Metric ? 1.0 + sx[i] * sx[i] : 1.0;
        const double my = Metric ? 1.0 + sy[i] * sy[i] : 1.0;
        wet[i] = w;
        still_x[i] = w * (hu[i] * hu[i] * mx <= rest2 * (d * d) ? 1.0 : 0.0);
        still_y[i] = w * (hv[i] * hv[i] * my <= rest2 * (d * d) ? 1.0 : 0.0);
        if constexpr (Velocity) {
            const VelocityQuotients q = velocity_quotients(d, hu[i], hv[i]);
            u[i] = q.u;
            v[i] = q.v;
        }
    }
}

// ---------------------------------------------------------------- the regime of a row

// The extends of cells a and b of row r in x.
AVALANCHE_INLINE double extends_x(const RegimeRowInput& in, const RegimeRowTerms& t, int a, int b) {
    return extends(in.hu[a], in.h[a], t.still_x[a], t.wet[a], in.hu[b], in.h[b], t.still_x[b],
                   t.wet[b]);
}

// Whether the central differences of cell i extend in both directions (1.0 or 0.0):
// then both regimes are active, whatever the second scales say (next_regime).
AVALANCHE_INLINE double central_extends(const RegimeRowInput& in, const RegimeRowTerms& t, int i,
                                        int im, int ip) {
    return extends_x(in, t, im, ip) *
           extends(in.hv_s[i], in.h_s[i], t.still_y_s[i], t.wet_s[i], in.hv_n[i], in.h_n[i],
                   t.still_y_n[i], t.wet_n[i]);
}

// The regime of cell i from its previous regime: x from the cells im, ip (one away)
// and imm, ipp (two away) of the row, y from the rows s, n, ss, nn.
template <bool Both>
AVALANCHE_INLINE void regime_lane(const RegimeRowInput& in, const RegimeRowTerms& t,
                                  RegimeFlags* regime, int i, int im, int ip, int imm, int ipp) {
    const auto y = [&](const double* qa, const double* ha, const double* sa, const double* wa,
                       const double* qb, const double* hb, const double* sb, const double* wb)
        __attribute__((always_inline)) { return extends(qa[i], ha[i], sa[i], wa[i], qb[i], hb[i], sb[i], wb[i]); };
    const double was = static_cast<double>(regime[i]);
    const double was_y = was >= kRegimeYActive ? 1.0 : 0.0, was_x = was - kRegimeYActive * was_y;
    const double x_active =
        next_regime<Both>(was_x, extends_x(in, t, im, ip), extends_x(in, t, im, i),
                          extends_x(in, t, i, ip), extends_x(in, t, imm, ipp));
    const double y_active = next_regime<Both>(
        was_y, y(in.hv_s, in.h_s, t.still_y_s, t.wet_s, in.hv_n, in.h_n, t.still_y_n, t.wet_n),
        y(in.hv_s, in.h_s, t.still_y_s, t.wet_s, in.hv, in.h, t.still_y, t.wet),
        y(in.hv, in.h, t.still_y, t.wet, in.hv_n, in.h_n, t.still_y_n, t.wet_n),
        y(in.hv_ss, in.h_ss, t.still_y_ss, t.wet_ss, in.hv_nn, in.h_nn, t.still_y_nn, t.wet_nn));
    const double now = kRegimeXActive * x_active + kRegimeYActive * y_active;
    regime[i] = static_cast<RegimeFlags>(t.wet[i] != 0.0 ? now : double{kRegimeAtStart});
}

// Cells are taken kBlock at a time: where the central differences of every cell of a
// block extend in both directions (all of a uniformly accelerating or spreading flow,
// and a deposit at rest), every regime is active and the second scales are not
// computed. The loops have a fixed trip count, so that they vectorise fully.
constexpr int kBlock = 16;

// Without tree-PRE: GCC 12 otherwise carries loads of one cell's neighbours over to the
// next cell, a loop-carried value its vectoriser rejects ("unknown def-use cycle"), and
// the loop stayed scalar: 10.6-29 ns per cell against 3.5 (bench_row_kernels). The
// attribute is GCC's; clang (the sanitizer build) has no such pass to turn off.
#if defined(__clang__)
#define AVALANCHE_NO_TREE_PRE
#else
#define AVALANCHE_NO_TREE_PRE __attribute__((optimize("no-tree-pre")))
#endif
template <bool Both>
AVALANCHE_NO_TREE_PRE AVALANCHE_SIMD_CLONES void from_terms_clone(
    const RegimeRowInput& input, const RegimeRowTerms& terms, RegimeFlags* regime, int i0, int i1,
    int lo, int hi) {
    // Local copies, so that GCC need not prove that the stores through regime leave the
    // caller's row pointers alone.
    const RegimeRowInput in = input;
    const RegimeRowTerms t = terms;
    // The cells whose differences need no clamp (vectorised, in blocks), then those
    // within two columns of the padding columns lo and hi, clamped.
    const int a = std::min(std::max(i0, lo + 2), i1), e = std::max(std::min(i1, hi - 1), a);
    int i = a;
    for (; i + kBlock <= e; i += kBlock) {
        double decided = 0.0;
#pragma omp simd reduction(+ : decided)
        for (int k = i; k < i + kBlock; ++k) decided += central_extends(in, t, k, k - 1, k + 1);
        if (decided == kBlock) {
#pragma omp simd
            for (int k = i; k < i + kBlock; ++k) regime[k] = kRegimeAtStart;  // both active
            continue;
        }
#pragma omp simd
        for (int k = i; k < i + kBlock; ++k) regime_lane<Both>(in, t, regime, k, k - 1, k + 1, k - 2, k + 2);
    }
#pragma omp simd
    for (int k = i; k < e; ++k) regime_lane<Both>(in, t, regime, k, k - 1, k + 1, k - 2, k + 2);
    const auto clamped = [&](int k) {
        regime_lane<Both>(in, t, regime, k, std::max(k - 1, lo), std::min(k + 1, hi),
                          std::max(k - 2, lo), std::min(k + 2, hi));
    };
    for (int k = i0; k < a; ++k) clamped(k);
    for (int k = e; k < i1; ++k) clamped(k);
}

}  // namespace

void regime_terms_row(const double* h, const double* hu, const double* hv, const double* sx,
                      const double* sy, double h_min, double rest_speed, const RegimeTermsRow& out,
                      int i0, int i1) noexcept {
    const double rest2 = rest_speed * rest_speed;
    const auto run = [&](auto metric, auto velocity) {
        terms_clone<decltype(metric)::value, decltype(velocity)::value>(
            h, hu, hv, sx, sy, h_min, rest2, out.wet, out.still_x, out.still_y, out.u, out.v, i0,
            i1);
    };
    using yes = std::true_type;
    using no = std::false_type;
    const bool velocity = out.u != nullptr;
    if (sx != nullptr)
        velocity ? run(yes{}, yes{}) : run(yes{}, no{});
    else
        velocity ? run(no{}, yes{}) : run(no{}, no{});
}

void regime_row_from_terms(const RegimeRowInput& in, const RegimeRowTerms& t,
                           RegimeFlags* regime, int i0, int i1, int lo, int hi) noexcept {
    if (in.confirm_at_both_scales)
        from_terms_clone<true>(in, t, regime, i0, i1, lo, hi);
    else
        from_terms_clone<false>(in, t, regime, i0, i1, lo, hi);
}

void regime_row(const RegimeRowInput& in, RegimeFlags* regime, double h_min, double rest_speed,
                int i0, int i1, int lo, int hi) noexcept {
    if (i1 <= i0) return;
    // Scratch rows over the columns lo .. hi: the terms of the five rows, three each.
    const std::ptrdiff_t width = hi + 1 - lo;
    std::vector<double> scratch(static_cast<std::size_t>(15 * width));
    const auto row = [&](int q) { return scratch.data() + q * width - lo; };  // column 0
    const auto terms_of = [&](int q) {
        return RegimeTermsRow{row(3 * q), row(3 * q + 1), row(3 * q + 2)};
    };
    // Row r over the columns its x-differences read; the others over [i0, i1). (Their
    // still_x is not read: they take their y-momentum and, in the DEM frame, their s_y
    // for the x-terms too; in bed-fitted frames every gradient row is null.)
    regime_terms_row(in.h, in.hu, in.hv, in.sx, in.sy, h_min, rest_speed, terms_of(0),
                     std::max(i0 - 2, lo), std::min(i1 + 2, hi + 1));
    const double* h_rows[4] = {in.h_s, in.h_n, in.h_ss, in.h_nn};
    const double* hv_rows[4] = {in.hv_s, in.hv_n, in.hv_ss, in.hv_nn};
    const double* sy_rows[4] = {in.sy_s, in.sy_n, in.sy_ss, in.sy_nn};
    for (int q = 0; q < 4; ++q)
        regime_terms_row(h_rows[q], hv_rows[q], hv_rows[q], sy_rows[q], sy_rows[q], h_min,
                         rest_speed, terms_of(q + 1), i0, i1);
    const RegimeRowTerms t{row(0), row(3), row(6), row(9),  row(12), row(1),
                           row(2), row(5), row(8), row(11), row(14)};
    regime_row_from_terms(in, t, regime, i0, i1, lo, hi);
}

}  // namespace avalanche
