// The advection's per-cell kernels (update_rows.hpp: donor factors and the conservative
// update with its velocity clamps; cell_rows.hpp: the pressure stage) must give
// bitwise what the whole-grid scalar loops of the stepper gave before they were
// vectorised. The references below are those loops (stepper.cpp, limit_and_update
// and update_pressure_coefficients, 2026-11-22), kept here as the definition (with
// the scalar cap_speed of energy_cap.hpp, which they called then). Rows
// mix empty, emptied, thin and wet cells, velocities inside and outside their own
// invariant bounds, cells with no wet neighbour, speeds over the own and the 3 x 3
// speed bound, and cells over the energy cap; some trials give the update a thin-layer
// depth, below which a cell gets zero momentum (2026-12-04). One change on purpose
// since (2026-12-02):
// a cell's two velocity quotients share one reciprocal, hu * (1 / h) and hv * (1 / h),
// in the kernels and in these references alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/energy_cap.hpp"
#include "avalanche/numerics/update_rows.hpp"
#include "avalanche/physics/dem_coefficients.hpp"
#include "support/same_bits.hpp"

using namespace avalanche;

namespace {

constexpr double kNoBound = std::numeric_limits<double>::max();

using test::same_bits;

// Three rows (r - 1, r, r + 1) of width w; the row under test is the middle one.
struct Rows {
    int w;
    std::vector<double> v;
    explicit Rows(int width, double fill = 0.0)
        : w(width), v(static_cast<std::size_t>(3 * width), fill) {}
    double* mid() { return v.data() + w; }
    const double* mid() const { return v.data() + w; }
};

}  // namespace

TEST(UpdateRows, DonorFactorsAndUpdateAreBitwiseTheScalarLoops) {
    std::mt19937_64 rng(20261206);
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
    const int w = 45;  // columns 1 .. w - 2 are updated: not a multiple of any vector width
    const double rx = 0.05, ry = 0.04, h_min = 1e-3, g = 9.81;
    long cells = 0, clamped = 0, emptied = 0, capped = 0, sped = 0;
    // Cells outside their own bounds that the block's bounds finish, cells with no wet
    // cell around, cells left thinner than h_thin (zero momentum: the thin-layer rule
    // gives them their velocity after the advection).
    long block_only = 0, no_wet_around = 0, thin = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const bool metric = trial % 2 == 1;
        const double budget = trial % 3 == 0 ? std::numeric_limits<double>::infinity() : g * 30.0;
        const double h_thin = trial % 5 == 2 ? 0.4 : 0.0;
        Rows fxh(w), fxu(w), fxv(w), fyh(w), fyu(w), fyv(w), h(w), hu(w), hv(w), elev(w), sx(w),
            sy(w);
        Rows ulo(w, kNoBound), uhi(w, -kNoBound), vlo(w, kNoBound), vhi(w, -kNoBound), shi(w);
        for (int k = 0; k < 3 * w; ++k) {
            const double kind = unit(rng);
            h.v[k] = kind < 0.15 ? 0.0 : kind < 0.22 ? 0.5 * h_min : 3.0 * unit(rng);
            const double u = 10.0 * sym(rng), v = 10.0 * sym(rng);
            hu.v[k] = h.v[k] * u;
            hv.v[k] = h.v[k] * v;
            // Fluxes: some large enough to empty their donor, some exactly zero.
            const double scale = unit(rng) < 0.2 ? 200.0 : 10.0;
            fxh.v[k] = unit(rng) < 0.1 ? 0.0 : scale * sym(rng);
            fyh.v[k] = unit(rng) < 0.1 ? 0.0 : scale * sym(rng);
            fxu.v[k] = 50.0 * sym(rng);
            fxv.v[k] = 50.0 * sym(rng);
            fyu.v[k] = 50.0 * sym(rng);
            fyv.v[k] = 50.0 * sym(rng);
            elev.v[k] = 40.0 * unit(rng);
            sx.v[k] = sym(rng);
            sy.v[k] = sym(rng);
            // A wet cell's bounds, some narrow enough to bind; every fourth trial has few,
            // so that some cells have no wet cell around.
            if (unit(rng) < (trial % 4 == 3 ? 0.05 : 0.8)) {
                const double a = unit(rng) < 0.3 ? 0.1 * unit(rng) : 20.0 * unit(rng);
                ulo.v[k] = u - a;
                uhi.v[k] = u + a;
                vlo.v[k] = v - a;
                vhi.v[k] = v + a;
                shi.v[k] = unit(rng) < 0.3 ? 2.0 * unit(rng) : 30.0;
            }
        }
        // Donor factors of all three rows by the kernel, against the reference.
        Rows factor(w, 1.0), factor_ref(w, 1.0);
        for (int r = 0; r < 3; ++r) {
            if (r == 2) continue;  // the reference needs the row above; the top row stays 1
            const int o = r * w;
            const FaceFluxRows f{fxh.v.data() + o, fxu.v.data() + o, fxv.v.data() + o,
                                 fyh.v.data() + o, fyu.v.data() + o, fyv.v.data() + o};
            donor_factor_row(f, h.v.data() + o, rx, ry, h_min, w, factor.v.data() + o, 1, w - 1);
            for (int i = 1; i < w - 1; ++i) {
                const int k = o + i;
                const double out = rx * (std::max(fxh.v[k + 1], 0.0) + std::max(-fxh.v[k], 0.0)) +
                                   ry * (std::max(fyh.v[k + w], 0.0) + std::max(-fyh.v[k], 0.0));
                double fr = 1.0;
                if (h.v[k] < h_min)
                    fr = 0.0;
                else if (out > h.v[k])
                    fr = h.v[k] / out;
                factor_ref.v[k] = fr;
                ASSERT_TRUE(same_bits(fr, factor.v[k])) << "trial " << trial << " factor " << k;
            }
        }
        // The update of the middle row, with the reference's factors.
        Rows nh(w, -7.0), nhu(w, -7.0), nhv(w, -7.0);
        const UpdateRowInput in{{fxh.mid(), fxu.mid(), fxv.mid(), fyh.mid(), fyu.mid(), fyv.mid()},
                                factor_ref.mid(),
                                ulo.mid(),
                                uhi.mid(),
                                vlo.mid(),
                                vhi.mid(),
                                shi.mid(),
                                h.mid(),
                                hu.mid(),
                                hv.mid(),
                                elev.mid(),
                                metric ? sx.mid() : nullptr,
                                metric ? sy.mid() : nullptr};
        update_row(in, UpdateRowParams{rx, ry, w, budget, g, h_thin}, nh.mid(), nhu.mid(),
                   nhv.mid(), 1, w - 1);
        const double* factor_r = factor_ref.v.data();
        const auto donor = [&](const std::vector<double>& fh, int k, int off) {
            return fh[k] == 0.0 ? 1.0 : factor_r[fh[k] > 0.0 ? k - off : k];
        };
        const auto min9 = [&](const Rows& f, int k) {
            double m = kNoBound;
            for (int r = k - w; r <= k + w; r += w)
                m = std::min({m, f.v[r - 1], f.v[r], f.v[r + 1]});
            return m;
        };
        const auto max9 = [&](const Rows& f, int k, double init) {
            double m = init;
            for (int r = k - w; r <= k + w; r += w)
                m = std::max({m, f.v[r - 1], f.v[r], f.v[r + 1]});
            return m;
        };
        for (int i = 1; i < w - 1; ++i) {
            const int k = w + i;
            // The reference: limit_and_update's loop body.
            double ref_h = 0.0, ref_hu = 0.0, ref_hv = 0.0;
            [&] {
                const double fw = donor(fxh.v, k, 1), fe = donor(fxh.v, k + 1, 1);
                const double fs = donor(fyh.v, k, w), fn = donor(fyh.v, k + w, w);
                double hn = h.v[k] - rx * (fxh.v[k + 1] * fe - fxh.v[k] * fw) -
                            ry * (fyh.v[k + w] * fn - fyh.v[k] * fs);
                if (hn < 0.0) hn = 0.0;
                ref_h = hn;
                const double qu = hu.v[k] - (rx * (fxu.v[k + 1] * fe - fxu.v[k] * fw) +
                                             ry * (fyu.v[k + w] * fn - fyu.v[k] * fs));
                const double qv = hv.v[k] - (rx * (fxv.v[k + 1] * fe - fxv.v[k] * fw) +
                                             ry * (fyv.v[k + w] * fn - fyv.v[k] * fs));
                if (hn <= 0.0) {
                    ++emptied;
                    return;
                }
                if (hn < h_thin) {
                    ++thin;
                    return;
                }
                const double inv = 1.0 / hn;  // one division for both quotients
                double u = qu * inv, v = qv * inv;
                const bool own = ulo.v[k] <= u && u <= uhi.v[k] && vlo.v[k] <= v && v <= vhi.v[k];
                if (!own) {
                    ++clamped;
                    const double lo = min9(ulo, k), hi = max9(uhi, k, -kNoBound);
                    if (lo > hi) {
                        ++no_wet_around;
                        return;
                    }
                    const double vl = min9(vlo, k), vh = max9(vhi, k, -kNoBound);
                    if (u < lo || u > hi) u = std::clamp(u, lo, hi);
                    if (v < vl || v > vh) v = std::clamp(v, vl, vh);
                }
                double speed2 = u * u + v * v;
                if (metric) {
                    const double ww = sx.v[k] * u + sy.v[k] * v;
                    speed2 += ww * ww;
                }
                const double bound = max9(shi, k, 0.0);
                const double cap2 = 2.0 * (budget - g * elev.v[k]);
                if (!own && !(speed2 > bound * bound) && speed2 <= cap2) ++block_only;
                if (speed2 > shi.v[k] * shi.v[k]) {
                    ++sped;
                    if (speed2 > bound * bound) {
                        const double scale = bound / std::sqrt(speed2);
                        u *= scale;
                        v *= scale;
                        speed2 = bound * bound;
                    }
                }
                if (speed2 > cap2) ++capped;
                cap_speed(u, v, speed2, cap2);
                ref_hu = hn * u;
                ref_hv = hn * v;
            }();
            ASSERT_TRUE(same_bits(ref_h, nh.v[k]) && same_bits(ref_hu, nhu.v[k]) &&
                        same_bits(ref_hv, nhv.v[k]))
                << "trial " << trial << " cell " << i << ": scalar (" << ref_h << ", " << ref_hu
                << ", " << ref_hv << ") row (" << nh.v[k] << ", " << nhu.v[k] << ", " << nhv.v[k]
                << ")";
            ++cells;
        }
    }
    EXPECT_EQ(cells, 60L * 43);
    // Every path of the update was taken.
    EXPECT_GT(emptied, 50);
    EXPECT_GT(clamped, 50);
    EXPECT_GT(sped, 50);
    EXPECT_GT(capped, 20);
    EXPECT_GT(block_only, 50);
    EXPECT_GT(no_wet_around, 20);
    EXPECT_GT(thin, 20);
}

TEST(UpdateRows, PressureRowIsBitwiseTheScalarLoop) {
    std::mt19937_64 rng(20261207);
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
    const int w = 41, ng = 2;  // columns -2 .. w - 3 with the padding clamp at both ends
    EarthPressureCoefficients kc;
    kc.kx_active = 0.6;
    kc.kx_passive = 2.4;
    kc.ky_given_kx_active_active = 0.5;
    kc.ky_given_kx_active_passive = 1.7;
    kc.ky_given_kx_passive_active = 0.9;
    kc.ky_given_kx_passive_passive = 3.1;
    const double k_max = 3.1, h_min = 1e-3;
    long active = 0, passive = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const bool isotropic = trial % 4 == 3, metric = trial % 2 == 1;
        Rows h(w), hu(w), hv(w), px(w), py(w), gn(w), nt(w), sx(w), sy(w);
        std::vector<RegimeFlags> regime(static_cast<std::size_t>(w));
        for (int k = 0; k < 3 * w; ++k) {
            const double kind = unit(rng);
            h.v[k] = kind < 0.15 ? 0.0 : kind < 0.22 ? 0.5 * h_min : 3.0 * unit(rng);
            // Some neighbours move alike (a vanishing gradient counts as active).
            const double u = kind > 0.8 ? 2.0 : 10.0 * sym(rng);
            hu.v[k] = h.v[k] * u;
            hv.v[k] = h.v[k] * (kind > 0.8 ? -1.0 : 10.0 * sym(rng));
            px.v[k] = 9.81 * unit(rng);
            py.v[k] = 9.81 * unit(rng);
            gn.v[k] = 9.81 * unit(rng);
            nt.v[k] = 0.5 + unit(rng);
            sx.v[k] = sym(rng);
            sy.v[k] = sym(rng);
            if (k < w) regime[static_cast<std::size_t>(k)] = static_cast<RegimeFlags>(4.0 * unit(rng));
        }
        // The load on a bed-normal depth, g_n times the normal-thickness factor: read in the
        // chute frame. With slopes (the DEM frame) the kernel computes px, py and it from
        // them (dem_coefficients, whose values test_dem_frame.cpp checks against their
        // quotients); the reference reads these.
        Rows gn_nt(w);
        for (int k = 0; k < 3 * w; ++k) gn_nt.v[k] = gn.v[k] * nt.v[k];
        const double g_slopes = 9.80665;
        if (metric)
            for (int k = 0; k < 3 * w; ++k) {
                const DemCoefficients c = dem_coefficients(sx.v[k], sy.v[k], g_slopes);
                px.v[k] = c.px;
                py.v[k] = c.py;
                gn_nt.v[k] = c.gn_nt;
            }
        // Column i of the row is element i + ng.
        const auto col0 = [&](Rows& f, int row) { return f.v.data() + row * w + ng; };
        // The velocity quotients hu / h, hv / h of every cell, as the stepper passes them.
        Rows qu(w), qv(w);
        for (int k = 0; k < 3 * w; ++k) {
            qu.v[k] = hu.v[k] * (1.0 / h.v[k]);
            qv.v[k] = hv.v[k] * (1.0 / h.v[k]);
        }
        const PressureRowInput in{col0(h, 1),
                                  col0(qu, 1),
                                  col0(qv, 1),
                                  col0(px, 1),
                                  col0(py, 1),
                                  col0(gn, 1),
                                  col0(nt, 1),
                                  metric ? col0(sx, 1) : nullptr,
                                  metric ? col0(sy, 1) : nullptr,
                                  regime.data() + ng,
                                  metric ? g_slopes : 0.0};
        std::vector<double> out_v(9 * static_cast<std::size_t>(w), -7.0);
        const auto out_at = [&](int a) { return out_v.data() + a * w + ng; };
        const PressureRowOutput out{out_at(0), out_at(1), out_at(2), out_at(3), out_at(4),
                                    out_at(5), out_at(6), out_at(7), out_at(8)};
        const int lo = -ng, hi = w - ng - 1;
        pressure_row(in, out, PressureRowParams{kc, k_max, h_min, isotropic}, lo, hi + 1);
        // The reference: update_pressure_coefficients' loop body, with the regime given.
        for (int i = lo; i <= hi; ++i) {
            const int k = w + i + ng;
            double cx = px.v[k], cy = py.v[k];
            if (!isotropic) {
                const RegimeFlags r = regime[static_cast<std::size_t>(i + ng)];
                const bool x_active = (r & kRegimeXActive) != 0, y_active = (r & kRegimeYActive) != 0;
                (x_active ? active : passive)++;
                cx = kc.kx(x_active) * px.v[k];
                cy = kc.ky(x_active, y_active) * py.v[k];
            }
            // The last two: the celerities hllc_flux takes, sqrt(c h) of a wet side, 0 of a dry
            // one.
            double ref[9] = {cx, cy, kNoBound, -kNoBound, kNoBound, -kNoBound, 0.0, 0.0, 0.0};
            const double hh = h.v[k];
            if (hh >= h_min && hh > 0.0) {
                const double u = hu.v[k] * (1.0 / hh), v = hv.v[k] * (1.0 / hh);
                const double ax = 2.0 * std::sqrt(cx * hh), ay = 2.0 * std::sqrt(cy * hh);
                ref[2] = u - ax;
                ref[3] = u + ax;
                ref[4] = v - ay;
                ref[5] = v + ay;
                double speed2 = u * u + v * v;
                if (metric) {
                    const double ww = sx.v[k] * u + sy.v[k] * v;
                    speed2 += ww * ww;
                }
                ref[6] = std::sqrt(speed2) + 2.0 * std::sqrt(k_max * gn_nt.v[k] * hh);
                ref[7] = std::sqrt(cx * hh);
                ref[8] = std::sqrt(cy * hh);
            }
            for (int a = 0; a < 9; ++a)
                ASSERT_TRUE(same_bits(ref[a], out_at(a)[i]))
                    << "trial " << trial << " column " << i << " output " << a << ": scalar "
                    << ref[a] << " row " << out_at(a)[i];
        }
    }
    EXPECT_GT(active, 100);
    EXPECT_GT(passive, 100);
}

TEST(UpdateRows, RegimeRowIsBitwiseTheScalarRule) {
    // Five rows (r - 2 .. r + 2) of random depths and momenta, random previous regimes;
    // the reference is the rule of regime_rows.hpp (regime_row) written as a plain loop.
    std::mt19937_64 rng(20261202);
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
    const int w = 75, ng = 2;  // columns -2 .. w - 3 with the padding clamp at both ends
    const double h_min = 1e-3, rest_speed = 0.5;
    long passive = 0, active = 0, kept = 0, reset = 0, at_rest = 0, with_dry = 0, one_scale = 0;
    // Stretches of 32 cells or more whose central differences all extend in x and y: the
    // kernel settles blocks of cells inside them without the second scales, and the
    // cells next to them with.
    long settled_stretches = 0;
    for (int trial = 0; trial < 60; ++trial) {
        // Trials from 40 on: a uniform flow (every difference extends) with a few cells
        // of their own, so that settled blocks alternate with unsettled ones.
        const bool uniform = trial >= 40;
        std::vector<double> h(5 * static_cast<std::size_t>(w)), hu(h.size()), hv(h.size());
        for (std::size_t k = 0; k < h.size(); ++k) {
            const double kind = !uniform || unit(rng) < 0.03 ? unit(rng) : 0.86 + 0.14 * unit(rng);
            h[k] = kind < 0.1 ? 0.0 : kind < 0.15 ? 0.5 * h_min : 3.0 * unit(rng);
            // Some neighbours move alike (a vanishing difference extends), some are
            // slower than the rest speed (a deposit's residue).
            const double speed = kind > 0.85 ? 0.0 : kind > 0.6 ? 0.55 : 10.0;
            hu[k] = h[k] * (kind > 0.85 ? 2.0 : speed * sym(rng));
            hv[k] = h[k] * (kind > 0.85 ? -1.0 : speed * sym(rng));
        }
        std::vector<RegimeFlags> before(static_cast<std::size_t>(w));
        for (auto& r : before) r = static_cast<RegimeFlags>(4.0 * unit(rng));
        std::vector<RegimeFlags> regime = before;
        // Odd trials in the DEM frame: surface gradients up to 2 (63 deg); trials 2, 3
        // of every four confirm a compression at both scales (the first-order scheme).
        const bool metric = trial % 2 == 1;
        const bool both = trial % 4 >= 2;
        std::vector<double> sx(h.size(), 0.0), sy(h.size(), 0.0);
        if (metric)
            for (std::size_t k = 0; k < h.size(); ++k) {
                sx[k] = 2.0 * sym(rng);
                sy[k] = 2.0 * sym(rng);
            }
        const auto col0 = [&](std::vector<double>& f, int row) { return f.data() + row * w + ng; };
        RegimeRowInput in{col0(h, 2),  col0(hu, 2), col0(hv, 2), col0(h, 1),
                          col0(hv, 1), col0(h, 3),  col0(hv, 3), col0(h, 0),
                          col0(hv, 0), col0(h, 4),  col0(hv, 4)};
        if (metric) {
            in.sx = col0(sx, 2);
            in.sy = col0(sy, 2);
            in.sy_s = col0(sy, 1);
            in.sy_n = col0(sy, 3);
            in.sy_ss = col0(sy, 0);
            in.sy_nn = col0(sy, 4);
        }
        in.confirm_at_both_scales = both;
        const int lo = -ng, hi = w - ng - 1;
        regime_row(in, regime.data() + ng, h_min, rest_speed, lo, hi + 1, lo, hi);
        // The reference: a velocity is (momentum, depth), at rest (0, 1) where thin or
        // dry; b - a compared multiplied out by both depths; two velocities whose
        // along-surface components (q/d sqrt(1 + s^2)) are within the rest speed are equal;
        // a difference with a thin or dry cell extends.
        const auto wet = [h_min](double d) { return d >= h_min && d > 0.0; };
        const double rest2 = rest_speed * rest_speed;
        // count: add to the tallies of the cases seen (not for the settled-stretch probe).
        const auto extends = [&](int ka, int kb, const std::vector<double>& q,
                                 const std::vector<double>& slope, bool count = true) {
            if (!wet(h[ka]) || !wet(h[kb])) {
                if (count) ++with_dry;
                return true;
            }
            const double qa = wet(h[ka]) ? q[ka] : 0.0, da = wet(h[ka]) ? h[ka] : 1.0;
            const double qb = wet(h[kb]) ? q[kb] : 0.0, db = wet(h[kb]) ? h[kb] : 1.0;
            const double ma = 1.0 + slope[ka] * slope[ka], mb = 1.0 + slope[kb] * slope[kb];
            const double x = qa * db, y = qb * da;
            const bool falls = y - x < -1e-12 * std::max(std::abs(x), std::abs(y));
            const bool rest = qa * qa * ma <= rest2 * (da * da) && qb * qb * mb <= rest2 * (db * db);
            if (count && falls && rest) ++at_rest;
            return !falls || rest;
        };
        // Cells ll, l, c, r, rr (element indices) of one direction.
        const auto next = [&](bool was, int ll, int l, int c, int r, int rr,
                              const std::vector<double>& q, const std::vector<double>& slope) {
            if (extends(l, r, q, slope)) return true;
            const bool one_sided = !extends(l, c, q, slope) && !extends(c, r, q, slope);
            const bool four_cells = !extends(ll, rr, q, slope);
            const bool confirmed = both ? one_sided && four_cells : one_sided || four_cells;
            if (one_sided != four_cells) ++one_scale;
            if (!confirmed) ++kept;
            return !confirmed && was;
        };
        int stretch = 0;
        for (int i = lo; i <= hi; ++i) {
            const int k = 2 * w + i + ng;
            const auto col = [&](int j) { return 2 * w + std::clamp(j, lo, hi) + ng; };
            const bool central = extends(col(i - 1), col(i + 1), hu, sx, false) &&
                                 extends(k - w, k + w, hv, sy, false);
            stretch = central ? stretch + 1 : 0;
            if (stretch == 32) ++settled_stretches;
            const RegimeFlags was = before[static_cast<std::size_t>(i + ng)];
            RegimeFlags ref = kRegimeAtStart;
            if (wet(h[k])) {
                const bool x = next((was & kRegimeXActive) != 0, col(i - 2), col(i - 1), k,
                                    col(i + 1), col(i + 2), hu, sx);
                const bool y = next((was & kRegimeYActive) != 0, k - 2 * w, k - w, k, k + w,
                                    k + 2 * w, hv, sy);
                ref = static_cast<RegimeFlags>((x ? kRegimeXActive : 0) | (y ? kRegimeYActive : 0));
                (x ? active : passive)++;
            } else {
                ++reset;
            }
            ASSERT_EQ(int{ref}, int{regime[static_cast<std::size_t>(i + ng)]})
                << "trial " << trial << " column " << i;
        }
    }
    EXPECT_GT(active, 100);
    EXPECT_GT(passive, 100);
    EXPECT_GT(kept, 100);
    EXPECT_GT(reset, 50);
    EXPECT_GT(at_rest, 100);  // falling differences that the rest speed cancels
    EXPECT_GT(with_dry, 100);  // differences with a thin or dry cell
    EXPECT_GT(one_scale, 100);  // compressions only one scale confirms: the modes differ
    EXPECT_GT(settled_stretches, 10);
}

TEST(UpdateRows, RegimeIsTheCentralDifferenceConfirmedAtASecondScaleElseKept) {
    // One row of wet cells, v = 0 (y active everywhere), u rising at 0.1 per cell (the flow
    // extends) except for one slow cell (a velocity minimum) and a stretch where u falls by
    // 0.2 per cell (the flow compresses). Expected regime in x per cell:
    //  - the cell before the slow one: central difference u[i+1] - u[i-1] = -0.3, but
    //    neither confirmed (its one-sided differences are +0.1 and -0.4; over four cells
    //    +0.4): it keeps the regime it had. A lone slow cell is what made patterns of
    //    passive cells grow when such a cell turned passive;
    //  - inside the falling stretch: central and both one-sided differences negative:
    //    passive;
    //  - at the stretch's two ends: central -0.1, one-sided differences of both signs,
    //    over four cells -0.2: passive (a compression the one-sided test alone misses),
    //    but where both scales must confirm (the first-order scheme's rule) it keeps the
    //    regime it had;
    //  - every other cell: central difference positive: active, whatever it was;
    //  - a dry cell: back to both active;
    //  - the cells beside it: a difference with a dry cell extends (the edge of a flow
    //    spreading into dry ground), so their central difference makes them active,
    //    although u falls from 0.7 to the dry cell's 0 (taken for a cell at rest, the
    //    one before it kept a passive regime).
    const int w = 30, ng = 2, dry = 27;
    std::vector<double> h(5 * static_cast<std::size_t>(w), 1.0), hu(h.size()), hv(h.size());
    const int slow = 8, fall0 = 16, fall1 = 22;  // u falls from cell fall0 to cell fall1
    std::vector<double> u(static_cast<std::size_t>(w));
    for (int c = 0; c < w; ++c) {
        const double top = 0.1 * fall0, bottom = top - 0.2 * (fall1 - fall0);
        u[static_cast<std::size_t>(c)] = c < fall0    ? 0.1 * c
                                         : c <= fall1 ? top - 0.2 * (c - fall0)
                                                      : bottom + 0.1 * (c - fall1);
    }
    u[slow] -= 0.5;
    for (int r = 0; r < 5; ++r)
        for (int c = 0; c < w; ++c) hu[static_cast<std::size_t>(r * w + c)] = u[static_cast<std::size_t>(c)];
    h[static_cast<std::size_t>(2 * w + dry)] = 0.0;
    hu[static_cast<std::size_t>(2 * w + dry)] = 0.0;
    const auto col0 = [&](std::vector<double>& f, int row) { return f.data() + row * w + ng; };
    RegimeRowInput in{col0(h, 2),  col0(hu, 2), col0(hv, 2), col0(h, 1),
                      col0(hv, 1), col0(h, 3),  col0(hv, 3), col0(h, 0),
                      col0(hv, 0), col0(h, 4),  col0(hv, 4)};
    const int lo = -ng, hi = w - ng - 1;
    for (const bool both : {false, true})
    for (const RegimeFlags was : {kRegimeAtStart, kRegimeYActive}) {  // x active, x passive
        in.confirm_at_both_scales = both;
        std::vector<RegimeFlags> regime(static_cast<std::size_t>(w), was);
        regime_row(in, regime.data() + ng, 1e-3, 0.0, lo, hi + 1, lo, hi);
        for (int c = 2; c + 2 < w; ++c) {  // the end columns see clamped differences
            const RegimeFlags got = regime[static_cast<std::size_t>(c)];
            if (c == dry) {
                EXPECT_EQ(got, kRegimeAtStart) << "dry cell";
                continue;
            }
            if (c == dry - 1 || c == dry + 1) {
                EXPECT_EQ(got, kRegimeAtStart) << "cell " << c << " beside the dry one";
                continue;
            }
            const bool end = c == fall0 || c == fall1;
            const bool kept = c == slow - 1 || (both && end);
            const bool passive = (c > fall0 && c < fall1) || (end && !both) ||
                                 (kept && (was & kRegimeXActive) == 0);
            EXPECT_EQ(got, passive ? kRegimeYActive : kRegimeAtStart)
                << "cell " << c << ", was " << int{was} << (both ? ", both scales" : "");
        }
    }
    // The cases that tell the rules apart: the central difference alone is negative before
    // the slow cell, the one-sided differences alone are mixed at the stretch's ends.
    EXPECT_LT(u[slow] - u[slow - 2], 0.0);
    EXPECT_GT(u[fall0] - u[fall0 - 1], 0.0);
    EXPECT_GT(u[fall1 + 1] - u[fall1], 0.0);
}

TEST(UpdateRows, RegimeTakesVelocitiesWithinTheRestSpeedForEqual) {
    // One row of wet cells whose u falls by 0.02 per cell from +0.1 to -0.1 (a deposit's
    // residue that compresses everywhere), with one cell at 0.4 in the middle.
    // With rest speed 0: every cell compresses, confirmed: passive. With rest speed 0.15:
    // the differences between cells within 0.15 vanish (active); the cells next to the
    // fast one see it outside the rest speed and stay decided by the differences.
    const int w = 24, ng = 2, fast = 12;
    std::vector<double> h(5 * static_cast<std::size_t>(w), 0.5), hu(h.size()), hv(h.size());
    std::vector<double> u(static_cast<std::size_t>(w));
    for (int c = 0; c < w; ++c) u[static_cast<std::size_t>(c)] = 0.1 - 0.2 * c / (w - 1);
    u[fast] = 0.4;
    for (int r = 0; r < 5; ++r)
        for (int c = 0; c < w; ++c)
            hu[static_cast<std::size_t>(r * w + c)] = 0.5 * u[static_cast<std::size_t>(c)];
    const auto col0 = [&](std::vector<double>& f, int row) { return f.data() + row * w + ng; };
    const RegimeRowInput in{col0(h, 2),  col0(hu, 2), col0(hv, 2), col0(h, 1),
                            col0(hv, 1), col0(h, 3),  col0(hv, 3), col0(h, 0),
                            col0(hv, 0), col0(h, 4),  col0(hv, 4)};
    const int lo = -ng, hi = w - ng - 1;
    for (const double rest : {0.0, 0.15}) {
        std::vector<RegimeFlags> regime(static_cast<std::size_t>(w), kRegimeAtStart);
        regime_row(in, regime.data() + ng, 1e-3, rest, lo, hi + 1, lo, hi);
        for (int c = 2; c + 2 < w; ++c) {
            const RegimeFlags got = regime[static_cast<std::size_t>(c)];
            if (c >= fast - 2 && c <= fast + 2) continue;  // the fast cell in their stencil
            EXPECT_EQ(got, rest == 0.0 ? kRegimeYActive : kRegimeAtStart)
                << "cell " << c << ", rest speed " << rest;
        }
        // The cell after the fast one: its central difference u[fast+2] - u[fast] = -0.42
        // involves the fast cell, so the rest speed does not cancel it. Confirmed without
        // a rest speed (passive); with it, its confirmations lie within the rest speed and
        // vanish, so the cell keeps its regime. A cell that was passive stays passive
        // (a cancelled central difference would have made it active).
        EXPECT_EQ(regime[static_cast<std::size_t>(fast + 1)],
                  rest == 0.0 ? kRegimeYActive : kRegimeAtStart)
            << "rest " << rest;
        std::vector<RegimeFlags> was_passive(static_cast<std::size_t>(w), kRegimeYActive);
        regime_row(in, was_passive.data() + ng, 1e-3, rest, lo, hi + 1, lo, hi);
        EXPECT_EQ(was_passive[static_cast<std::size_t>(fast + 1)], kRegimeYActive) << "rest " << rest;
        EXPECT_EQ(was_passive[5], rest == 0.0 ? kRegimeYActive : kRegimeAtStart) << "rest " << rest;
    }
}
