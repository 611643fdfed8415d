// The vectorised per-cell row kernels (cell_rows.hpp) must give bitwise what the
// stepper's scalar loops gave before they were vectorised. The references below are
// those loops as they stood (stepper.cpp, apply_sources and stable_dt, 2026-11-22),
// kept here as the definition (they call the scalar cap_speed of energy_cap.hpp, which
// they called then). Rows mix dry, thin, moving, stopping and capped cells,
// with and without curvature and metric terms, one and several sub-steps. One change on
// purpose since (2026-12-02): a cell's two velocity quotients share one reciprocal,
// hu * (1 / h) and hv * (1 / h), in the kernels and in these references alike.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "avalanche/numerics/cell_rows.hpp"
#include "avalanche/numerics/energy_cap.hpp"
#include "avalanche/physics/dem_coefficients.hpp"
#include "support/same_bits.hpp"

using namespace avalanche;

namespace {

using test::same_bits;

struct Row {
    std::vector<double> h, hu, hv, ax, ay, gn, elev, cxx, cxy, cyy, sx, sy, px, py;
};

Row random_row(std::mt19937_64& rng, int n) {
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
    Row r;
    for (auto* f : {&r.h, &r.hu, &r.hv, &r.ax, &r.ay, &r.gn, &r.elev, &r.cxx, &r.cxy, &r.cyy, &r.sx,
                    &r.sy, &r.px, &r.py})
        f->resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        const double kind = unit(rng);
        r.h[i] = kind < 0.2 ? 0.0 : kind < 0.3 ? 1e-6 : 5.0 * unit(rng);
        const double speed =
            kind > 0.9 ? 0.01 * unit(rng) : 30.0 * unit(rng);  // some stop by friction
        r.hu[i] = r.h[i] * speed * sym(rng);
        r.hv[i] = r.h[i] * speed * sym(rng);
        r.ax[i] = 5.0 * sym(rng);
        r.ay[i] = 5.0 * sym(rng);
        r.gn[i] = 9.81 * unit(rng);
        r.elev[i] =
            100.0 * unit(rng);  // with the budget below, some cells capped, some above reach
        r.cxx[i] = 0.05 * sym(rng);
        r.cxy[i] = 0.05 * sym(rng);
        r.cyy[i] = 0.05 * sym(rng);
        r.sx[i] = sym(rng);
        r.sy[i] = sym(rng);
        r.px[i] = 9.81 * unit(rng);
        r.py[i] = 9.81 * unit(rng);
    }
    return r;
}

// The DEM frame's coefficients of every cell from its slopes sx, sy (dem_coefficients,
// whose values test_dem_frame.cpp checks against their quotients): with slopes the kernels
// compute these instead of reading them.
void dem_coefficients_of_slopes(Row& r, double g) {
    for (std::size_t i = 0; i < r.sx.size(); ++i) {
        const DemCoefficients c = dem_coefficients(r.sx[i], r.sy[i], g);
        r.ax[i] = c.ax;
        r.ay[i] = c.ay;
        r.px[i] = c.px;
        r.py[i] = c.py;
        r.gn[i] = c.gn;
    }
}

}  // namespace

TEST(CellRows, SourcesRowIsBitwiseTheScalarSourceLoop) {
    std::mt19937_64 rng(20261203);
    const int n = 53;  // not a multiple of any vector width
    long cells = 0, capped = 0, stopped = 0;
    for (int trial = 0; trial < 64; ++trial) {
        const bool curv = trial % 2 == 1, metric = (trial / 2) % 2 == 1;
        const int m = trial % 8 < 4 ? 1 : 3;
        const double dt = 0.05, td = 0.4, g = 9.81;
        const double budget = trial % 16 < 8 ? g * 60.0 : std::numeric_limits<double>::infinity();
        Row r = random_row(rng, n);
        // With slopes (the DEM frame) the kernel computes ax, ay, gn from them.
        const double g_slopes = 9.80665;
        if (metric) dem_coefficients_of_slopes(r, g_slopes);
        Row ref = r;
        // The reference: apply_sources' loop body.
        const double sub = dt / m;
        for (int i = 0; i < n; ++i) {
            if (ref.h[i] <= 0.0) continue;
            const double inv = 1.0 / ref.h[i];  // one division for both quotients
            double u = ref.hu[i] * inv, v = ref.hv[i] * inv;
            double after2 = 0.0;
            for (int k = 0; k < m; ++k) {
                u += sub * ref.ax[i];
                v += sub * ref.ay[i];
                double load = ref.gn[i];
                if (curv)
                    load += ref.cxx[i] * u * u + 2.0 * ref.cxy[i] * u * v + ref.cyy[i] * v * v;
                load = std::max(load, 0.0);
                double speed2 = u * u + v * v;
                if (metric) {
                    const double w = ref.sx[i] * u + ref.sy[i] * v;
                    speed2 += w * w;
                }
                const double speed = std::sqrt(speed2);
                const double f = td * load * sub;
                if (speed <= f) {
                    u = v = 0.0;
                    after2 = 0.0;
                } else {
                    const double scale = 1.0 - f / speed;
                    u *= scale;
                    v *= scale;
                    after2 = (speed - f) * (speed - f);
                }
            }
            const double cap2 = 2.0 * (budget - g * ref.elev[i]);
            if (after2 > cap2) ++capped;
            if (u == 0.0 && v == 0.0) ++stopped;
            cap_speed(u, v, after2, cap2);
            ref.hu[i] = ref.h[i] * u;
            ref.hv[i] = ref.h[i] * v;
        }
        const SourceRowTerrain t{r.ax.data(),
                                 r.ay.data(),
                                 r.gn.data(),
                                 r.elev.data(),
                                 curv ? r.cxx.data() : nullptr,
                                 curv ? r.cxy.data() : nullptr,
                                 curv ? r.cyy.data() : nullptr,
                                 metric ? r.sx.data() : nullptr,
                                 metric ? r.sy.data() : nullptr,
                                 metric ? g_slopes : 0.0};
        apply_sources_row(r.h.data(), r.hu.data(), r.hv.data(), t,
                          SourceRowParams{sub, m, td, g, budget}, 0, n);
        for (int i = 0; i < n; ++i) {
            ASSERT_TRUE(same_bits(r.h[i], ref.h[i]) && same_bits(r.hu[i], ref.hu[i]) &&
                        same_bits(r.hv[i], ref.hv[i]))
                << "trial " << trial << " cell " << i << ": scalar (" << ref.hu[i] << ", "
                << ref.hv[i] << ") row (" << r.hu[i] << ", " << r.hv[i] << ")";
            ++cells;
        }
    }
    EXPECT_EQ(cells, 64 * n);
    EXPECT_GT(capped, 50);   // the energy cap acted
    EXPECT_GT(stopped, 50);  // friction stopped cells
}

// Odd trials in the DEM frame: the kernel computes px, py from the slopes (not read,
// null), the reference reads the values dem_terrain stored before 2026-12-05.
TEST(CellRows, CflRateRowIsTheScalarMaximum) {
    std::mt19937_64 rng(20261204);
    const double g_slopes = 9.81;
    for (int trial = 0; trial < 50; ++trial) {
        const int n = 40 + trial;
        const bool metric = trial % 2 == 1;
        Row r = random_row(rng, n);
        if (metric) dem_coefficients_of_slopes(r, g_slopes);
        const double kx = 1.7, ky = 0.6, dx = 5.0, dy = 4.0, h_min = 1e-4;
        double ref = 0.0;
        for (int i = 0; i < n; ++i) {
            if (r.h[i] < h_min || r.h[i] <= 0.0) continue;
            const double inv = 1.0 / r.h[i];
            const double u = r.hu[i] * inv, v = r.hv[i] * inv;
            const double rx = (std::abs(u) + std::sqrt(kx * r.px[i] * r.h[i])) / dx;
            const double ry = (std::abs(v) + std::sqrt(ky * r.py[i] * r.h[i])) / dy;
            ref = std::max(ref, std::max(rx, ry));
        }
        const CflRowTerrain t = metric ? CflRowTerrain{nullptr, nullptr, r.sx.data(), r.sy.data(), g_slopes}
                                       : CflRowTerrain{r.px.data(), r.py.data()};
        const double got = cfl_rate_row(r.h.data(), r.hu.data(), r.hv.data(), t, kx, ky, dx, dy,
                                        h_min, 0, n);
        ASSERT_TRUE(same_bits(ref, got))
            << "trial " << trial << ": scalar " << ref << " row " << got;
        ASSERT_GT(ref, 0.0);
    }
    // A row without a wet cell has rate 0.
    std::vector<double> dry(17, 0.0), p(17, 9.81);
    EXPECT_EQ(cfl_rate_row(dry.data(), dry.data(), dry.data(), CflRowTerrain{p.data(), p.data()},
                           1.0, 1.0, 1.0, 1.0, 1e-4, 0, 17),
              0.0);
}

// The time loop's row scan (state_scan_row): its energy is the sum of (hu^2 + hv^2) / h
// over the cells with h > 0 in the grouping cell_rows.hpp defines (cell i0 + 8 k + l
// into partial sum l, the partial sums added in order), bit for bit whatever the
// vector width, and within round-off of a long double sum; it finds the first bad cell
// wherever it lies in a group of eight or in the row's tail.
TEST(CellRows, StateScanRowSumsInItsFixedGroupingAndNamesTheFirstBadCell) {
    std::mt19937_64 rng(20261203);
    for (int trial = 0; trial < 60; ++trial) {
        const int i0 = trial % 9, n = trial < 50 ? trial : 1000 + trial;
        const Row r = random_row(rng, i0 + n + 3);
        double partial[8] = {};
        long double exact = 0.0L;
        bool moving = false;
        for (int i = i0; i < i0 + n; ++i) {
            const double hh = r.h[i], qx = r.hu[i], qy = r.hv[i];
            if (hh > 0.0) {
                partial[(i - i0) % 8] += (qx * qx + qy * qy) / hh;
                exact += (static_cast<long double>(qx) * qx + static_cast<long double>(qy) * qy) / hh;
            }
            moving = moving || qx != 0.0 || qy != 0.0;
        }
        double grouped = 0.0;
        for (const double p : partial) grouped += p;
        const StateRowScan got =
            state_scan_row(r.h.data(), r.hu.data(), r.hv.data(), i0, i0 + n);
        ASSERT_TRUE(same_bits(grouped, got.twice_kinetic))
            << "trial " << trial << ": grouped " << grouped << " row " << got.twice_kinetic;
        EXPECT_NEAR(got.twice_kinetic, static_cast<double>(exact),
                    1e-15 * n * static_cast<double>(exact));
        EXPECT_EQ(got.moving, moving);
        EXPECT_EQ(got.first_bad, -1);
    }

    // The first bad cell at every position of a 21-cell row (two groups and a tail),
    // with a second bad cell after it; a row at rest but for one cell.
    constexpr int n = 21, i0 = 2;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (int p = i0; p < i0 + n; ++p) {
        for (int kind = 0; kind < 5; ++kind) {
            std::vector<double> h(n + 4, 1.0), hu(n + 4, 0.0), hv(n + 4, 0.0);
            h[i0] = -0.0;  // a negative zero is no negative depth
            h[i0 + 1] = 0.0;
            double* field[] = {h.data(), hu.data(), hv.data(), h.data(), hv.data()};
            const double value[] = {nan, inf, nan, -1e-300, -inf};
            field[kind][p] = value[kind];
            if (p + 3 < i0 + n) h[p + 3] = -1.0;
            const StateRowScan got = state_scan_row(h.data(), hu.data(), hv.data(), i0, i0 + n);
            EXPECT_EQ(got.first_bad, p) << "kind " << kind;
        }
        std::vector<double> h(n + 4, 1.0), hu(n + 4, 0.0), hv(n + 4, 0.0);
        EXPECT_FALSE(state_scan_row(h.data(), hu.data(), hv.data(), i0, i0 + n).moving);
        hv[p] = -1e-310;  // subnormal: still moving
        const StateRowScan got = state_scan_row(h.data(), hu.data(), hv.data(), i0, i0 + n);
        EXPECT_TRUE(got.moving) << p;
        EXPECT_EQ(got.first_bad, -1);
        EXPECT_EQ(got.twice_kinetic, 1e-310 * 1e-310);  // underflows to 0
    }
}
