// The vectorised row kernels of the stepper (face_flux_rows.hpp) must give bitwise
// the fluxes of the scalar kernels they were written from: hllc_flux (riemann_hllc.hpp)
// and waf_face_flux (waf_face.hpp), for every limiter, along x (neighbours adjacent
// in memory) and along y (neighbours a row stride apart), on rows whose lengths are
// not multiples of any vector width. The states mix empty, thin (below h_dry) and wet
// cells, equal neighbours (flat jumps: the limiter's special cases), and sub- and
// supercritical flow in both directions, so every selection in the kernels is taken.
// The kernels get the cells' velocity quotients q / h and celerities sqrt(c h) as arrays,
// as the stepper passes them (the celerities from celerity_row, itself checked here).
// (The stepper's quotients share one reciprocal per cell since 2026-12-02, q * (1 / h);
// here they are divided, as the scalar kernels divide: the face kernels' arithmetic
// from given quotients is what is compared. The predictor's own quotients of the
// predicted values share one reciprocal, and its reference below does the same.)

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "avalanche/numerics/face_flux_rows.hpp"
#include "avalanche/numerics/riemann_hllc.hpp"
#include "avalanche/numerics/waf_face.hpp"
#include "support/same_bits.hpp"

using namespace avalanche;

namespace {

using test::same_bits;

// A (2 + rows + 2) x width block of cells with random states; row r of faces reads
// rows r-2 .. r+1 along y.
struct Block {
    int width, rows;
    std::vector<double> h, qn, qt, c;
    std::vector<double> un, ut;  // the quotients qn / h, qt / h, as the stepper passes them
    std::vector<double> a;       // the celerities, from celerity_row
};

// all_wet: every cell at least h_dry thick (rows without a front take the kernels'
// second-order-only path).
Block random_block(std::mt19937_64& rng, int width, int rows, double h_dry, bool all_wet = false) {
    std::uniform_real_distribution<double> depth(0.0, 5.0), speed(-40.0, 40.0), coeff(0.1, 12.0),
        unit(0.0, 1.0);
    Block b{width, rows, {}, {}, {}, {}, {}, {}, {}};
    const std::size_t n = static_cast<std::size_t>(width) * (rows + 4);
    b.h.resize(n);
    b.qn.resize(n);
    b.qt.resize(n);
    b.c.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const double kind = unit(rng);
        if (k > 0 && kind < 0.15) {  // a copy of the neighbour: flat jumps
            b.h[k] = b.h[k - 1];
            b.qn[k] = b.qn[k - 1];
            b.qt[k] = b.qt[k - 1];
            b.c[k] = b.c[k - 1];
            continue;
        }
        b.h[k] = all_wet       ? depth(rng) + h_dry
                 : kind < 0.25 ? 0.0
                 : kind < 0.35 ? 0.5 * h_dry
                               : depth(rng) + h_dry;
        b.qn[k] = b.h[k] * (kind > 0.9 ? 0.0 : speed(rng));
        b.qt[k] = b.h[k] * speed(rng);
        b.c[k] = coeff(rng);
    }
    b.un.resize(n);
    b.ut.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        b.un[k] = b.qn[k] / b.h[k];
        b.ut[k] = b.qt[k] / b.h[k];
    }
    b.a.resize(n);
    celerity_row(b.h.data(), b.c.data(), h_dry, b.a.data(), static_cast<int>(n));
    return b;
}

// Cell k at depth h and at rest, its quotients 0 / h as the stepper passes them (NaN
// where h = 0); its celerity is left to the caller's celerity_row.
void set_at_rest(Block& b, std::size_t k, double h) {
    b.h[k] = h;
    b.qn[k] = b.qt[k] = 0.0;
    b.un[k] = b.qn[k] / h;
    b.ut[k] = b.qt[k] / h;
}

Conserved at(const Block& b, std::ptrdiff_t k) { return {b.h[k], b.qn[k], b.qt[k]}; }

// Compares one kernel with its scalar reference on every face of the block's rows,
// along x (off = 1, faces 2 .. width-2 of each row) and along y (off = width).
template <class RowKernel, class Reference>
long compare(const Block& b, RowKernel row, Reference reference) {
    long faces = 0;
    // Assigned in the loop, not made there: GCC 12 took the vectors made inside this loop
    // over an initializer list for a non-heap object (-Wfree-nonheap-object, a false
    // positive).
    std::vector<double> fh, fq, ft;
    for (const std::ptrdiff_t off : {std::ptrdiff_t{1}, static_cast<std::ptrdiff_t>(b.width)}) {
        fh.assign(b.h.size(), -1.0);
        fq.assign(b.h.size(), -1.0);
        ft.assign(b.h.size(), -1.0);
        for (int r = 2; r < b.rows + 2; ++r) {
            const std::ptrdiff_t k0 = static_cast<std::ptrdiff_t>(r) * b.width + 2;
            const int n = b.width - 3;  // faces k0 .. k0 + n - 1 keep k - 2, k + 1 in the row
            FaceRowInput in{b.h.data() + k0, b.qn.data() + k0, b.qt.data() + k0, b.c.data() + k0,
                            off};
            in.un = b.un.data() + k0;
            in.ut = b.ut.data() + k0;
            in.a = b.a.data() + k0;
            const FaceRowOutput out{fh.data() + k0, fq.data() + k0, ft.data() + k0};
            row(in, out, n);
            for (std::ptrdiff_t k = k0; k < k0 + n; ++k) {
                const Conserved ref = reference(at(b, k - 2 * off), at(b, k - off), at(b, k),
                                                at(b, k + off), b.c[k - off], b.c[k]);
                EXPECT_TRUE(same_bits(ref.h, fh[k]) && same_bits(ref.qn, fq[k]) &&
                            same_bits(ref.qt, ft[k]))
                    << "face " << k << " off " << off << ": scalar (" << ref.h << ", " << ref.qn
                    << ", " << ref.qt << ") row (" << fh[k] << ", " << fq[k] << ", " << ft[k]
                    << ")";
                if (::testing::Test::HasFailure()) return faces;
                ++faces;
            }
        }
    }
    return faces;
}

// compare() for the WAF row with van Leer at dt/dx = 0.01; tally(qll, ql, qr, qrr) sees
// each face's stencil (for the tests' counts of the cases met).
template <class Tally>
long compare_waf_van_leer(const Block& b, double h_dry, Tally tally) {
    return compare(
        b,
        [&](const FaceRowInput& in, const FaceRowOutput& out, int n) {
            waf_face_row(in, out, n, h_dry, 0.01, Limiter::van_leer);
        },
        [&](const Conserved& qll, const Conserved& ql, const Conserved& qr, const Conserved& qrr,
            double cl, double cr) {
            tally(qll, ql, qr, qrr);
            return waf_face_flux(qll, ql, qr, qrr, cl, cr, h_dry, 0.01, Limiter::van_leer);
        });
}

}  // namespace

TEST(FaceFluxRows, CelerityRowIsTheScalarCelerityOfEachSide) {
    std::mt19937_64 rng(20261208);
    const double h_dry = 1e-3;
    const Block b = random_block(rng, 53, 9, h_dry);
    long dry = 0;
    for (std::size_t k = 0; k < b.h.size(); ++k) {
        // hllc_flux (riemann_hllc.hpp): a side thinner than h_dry counts as empty.
        const double hh = b.h[k] >= h_dry && b.h[k] > 0.0 ? b.h[k] : 0.0;
        dry += hh == 0.0;
        ASSERT_TRUE(same_bits(std::sqrt(b.c[k] * hh), b.a[k])) << "cell " << k;
    }
    EXPECT_GT(dry, 50);
}

TEST(FaceFluxRows, FirstOrderRowIsBitwiseTheScalarHllcFlux) {
    std::mt19937_64 rng(20261201);
    const double h_dry = 1e-3;
    long faces = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const Block b = random_block(rng, 37 + trial % 9, 7, h_dry);
        faces += compare(
            b,
            [&](const FaceRowInput& in, const FaceRowOutput& out, int n) {
                hllc_face_row(in, out, n, h_dry);
            },
            [&](const Conserved&, const Conserved& ql, const Conserved& qr, const Conserved&,
                double cl, double cr) { return hllc_flux(ql, qr, cl, cr, h_dry); });
        if (HasFailure()) return;
    }
    EXPECT_GT(faces, 40 * 2 * 7 * 30);
}

TEST(FaceFluxRows, WafRowIsBitwiseTheScalarWafFaceFluxForEveryLimiter) {
    std::mt19937_64 rng(20261202);
    const double h_dry = 1e-3;
    for (const Limiter lim :
         {Limiter::superbee, Limiter::van_leer, Limiter::van_albada, Limiter::minmod}) {
        long faces = 0, waf_faces = 0;
        for (int trial = 0; trial < 40; ++trial) {
            const double dt_dx = 0.002 + 0.001 * trial;  // Courant numbers from small to above 1
            const Block b = random_block(rng, 37 + trial % 9, 7, h_dry,
                                         trial % 4 == 3);  // every fourth block: no fronts
            faces += compare(
                b,
                [&](const FaceRowInput& in, const FaceRowOutput& out, int n) {
                    waf_face_row(in, out, n, h_dry, dt_dx, lim);
                },
                [&](const Conserved& qll, const Conserved& ql, const Conserved& qr,
                    const Conserved& qrr, double cl, double cr) {
                    if (qll.h >= h_dry && ql.h >= h_dry && qr.h >= h_dry && qrr.h >= h_dry)
                        ++waf_faces;
                    return waf_face_flux(qll, ql, qr, qrr, cl, cr, h_dry, dt_dx, lim);
                });
            if (HasFailure()) return;
        }
        EXPECT_GT(faces, 40 * 2 * 7 * 30);
        // The second-order branch (no front in the stencil) was exercised, not only
        // the first-order fallback.
        EXPECT_GT(waf_faces, 2000) << "limiter " << static_cast<int>(lim);
    }
}

// States from a few values, so that faces meet the exact cases random states miss: a
// wave at rest (s = 0 exactly: the WAF weight's own case, a zero of either sign), a
// mirror-symmetric face (contact at rest), upwind and local jumps exactly equal, zero
// or of opposite signs (the limiter's cases), and negative zeros among the momenta.
TEST(FaceFluxRows, WafRowIsBitwiseTheScalarWafFaceFluxOnRestingAndSymmetricStates) {
    std::mt19937_64 rng(20261206);
    const double h_dry = 1e-3;
    const double depths[] = {1.0, 2.0}, speeds[] = {-2.0, -1.5, -0.0, 0.0, 1.5, 2.0};
    std::uniform_int_distribution<int> pick_depth(0, 1), pick_speed(0, 5);
    for (const Limiter lim :
         {Limiter::superbee, Limiter::van_leer, Limiter::van_albada, Limiter::minmod}) {
        long faces = 0, contact_at_rest = 0, outer_at_rest = 0;
        for (int trial = 0; trial < 20; ++trial) {
            Block b = random_block(rng, 37 + trial % 9, 7, h_dry, true);
            for (std::size_t k = 0; k < b.h.size(); ++k) {
                b.h[k] = depths[pick_depth(rng)];
                b.qn[k] = b.h[k] * speeds[pick_speed(rng)];
                b.qt[k] = b.h[k] * speeds[pick_speed(rng)];
                b.c[k] = 4.0;  // celerities 2 and 2 sqrt(2): u = +-2 at h = 1 is critical
                b.un[k] = b.qn[k] / b.h[k];
                b.ut[k] = b.qt[k] / b.h[k];
            }
            celerity_row(b.h.data(), b.c.data(), h_dry, b.a.data(), static_cast<int>(b.h.size()));
            const double dt_dx = 0.1;
            faces += compare(
                b,
                [&](const FaceRowInput& in, const FaceRowOutput& out, int n) {
                    waf_face_row(in, out, n, h_dry, dt_dx, lim);
                },
                [&](const Conserved& qll, const Conserved& ql, const Conserved& qr,
                    const Conserved& qrr, double cl, double cr) {
                    const HllcFan fan = hllc_fan(ql, qr, cl, cr, h_dry);
                    contact_at_rest += fan.s_star == 0.0 ? 1 : 0;
                    outer_at_rest += fan.s_l == 0.0 || fan.s_r == 0.0 ? 1 : 0;
                    return waf_face_flux(qll, ql, qr, qrr, cl, cr, h_dry, dt_dx, lim);
                });
            if (HasFailure()) return;
        }
        // The cases were met: faces with the contact at rest, and faces with an outer
        // wave at rest (a critical side, u - a = 0 exactly, and a supercritical other).
        EXPECT_GT(contact_at_rest, faces / 20) << "limiter " << static_cast<int>(lim);
        EXPECT_GT(outer_at_rest, 20) << "limiter " << static_cast<int>(lim);
    }
}

// Long rows wet but for a few thin cells: runs of faces without a front longer than the
// kernel's blocks of 16, ending anywhere within a block.
TEST(FaceFluxRows, WafRowWithScatteredFrontsIsBitwiseTheScalarWafFaceFlux) {
    std::mt19937_64 rng(20261205);
    const double h_dry = 1e-3;
    long faces = 0, waf_faces = 0;
    for (int trial = 0; trial < 12; ++trial) {
        Block b = random_block(rng, 150 + 7 * trial, 5, h_dry, true);
        std::uniform_int_distribution<std::size_t> cell(0, b.h.size() - 1);
        for (int k = 0; k < 6; ++k) {  // a few thin cells, each a front for its stencils
            set_at_rest(b, cell(rng), 0.5 * h_dry);
        }
        celerity_row(b.h.data(), b.c.data(), h_dry, b.a.data(), static_cast<int>(b.h.size()));
        faces += compare_waf_van_leer(
            b, h_dry,
            [&](const Conserved& qll, const Conserved& ql, const Conserved& qr,
                const Conserved& qrr) {
                if (qll.h >= h_dry && ql.h >= h_dry && qr.h >= h_dry && qrr.h >= h_dry) ++waf_faces;
            });
        if (HasFailure()) return;
    }
    // Most faces second order, some at a front.
    EXPECT_GT(waf_faces, faces * 8 / 10);
    EXPECT_LT(waf_faces, faces);
}

// Rows with long dry stretches, as an active box around a real flow has: the kernels
// write the zero flux of the faces between two dry cells without computing it, in runs
// longer than their blocks of 16 faces that start and end anywhere within a block.
// Every face's flux is compared (compare() presets the outputs to -1), both directions.
TEST(FaceFluxRows, RowsWithLongDryStretchesAreBitwiseTheScalarFluxes) {
    std::mt19937_64 rng(20261207);
    const double h_dry = 1e-3;
    long faces = 0, dry_faces = 0;
    for (int trial = 0; trial < 12; ++trial) {
        Block b = random_block(rng, 150 + 11 * trial, 5, h_dry, true);
        std::uniform_int_distribution<int> length(17, 70), kind(0, 2);
        for (int r = 0; r < b.rows + 4; ++r) {
            for (int i = length(rng) % 9; i < b.width;) {
                const int end = std::min(i + length(rng), b.width);
                const int k = kind(rng);  // empty, thin, or a mix of both
                for (; i < end; ++i) {
                    const bool empty = k == 0 || (k == 2 && i % 3 == 0);
                    set_at_rest(b, static_cast<std::size_t>(r) * b.width + i,
                                empty ? 0.0 : 0.5 * h_dry);
                }
                i += length(rng);  // a wet stretch
            }
        }
        celerity_row(b.h.data(), b.c.data(), h_dry, b.a.data(), static_cast<int>(b.h.size()));
        faces += compare_waf_van_leer(
            b, h_dry,
            [&](const Conserved&, const Conserved& ql, const Conserved& qr, const Conserved&) {
                dry_faces += ql.h < h_dry && qr.h < h_dry ? 1 : 0;
            });
        if (HasFailure()) return;
        compare(
            b,
            [&](const FaceRowInput& in, const FaceRowOutput& out, int n) {
                hllc_face_row(in, out, n, h_dry);
            },
            [&](const Conserved&, const Conserved& ql, const Conserved& qr, const Conserved&,
                double cl, double cr) { return hllc_flux(ql, qr, cl, cr, h_dry); });
        if (HasFailure()) return;
    }
    // A good share of the faces dry, runs of them longer than the kernels' blocks.
    EXPECT_GT(dry_faces, faces / 5);
    EXPECT_LT(dry_faces, faces * 4 / 5);
}

TEST(FaceFluxRows, PredictorRowIsTheScalarHalfStep) {
    std::mt19937_64 rng(20261205);
    const double h_dry = 1e-3, ratio = 0.37;
    long emptied = 0, kept = 0;
    for (int trial = 0; trial < 20; ++trial) {
        const Block q = random_block(rng, 41 + trial, 5, h_dry);
        const Block f =
            random_block(rng, 41 + trial, 5, h_dry);  // any numbers serve as face fluxes
        for (const std::ptrdiff_t off : {std::ptrdiff_t{1}, static_cast<std::ptrdiff_t>(q.width)}) {
            std::vector<double> ph(q.h.size()), pq(q.h.size()), pt(q.h.size()), pu(q.h.size()),
                pv(q.h.size());
            const std::ptrdiff_t k0 = 2 * q.width + 1;
            const int n = 3 * q.width;
            FaceRowInput in{q.h.data() + k0, q.qn.data() + k0, q.qt.data() + k0,
                            q.c.data() + k0, off};
            in.un = q.un.data() + k0;  // the state's quotients, as the stepper passes them
            in.ut = q.ut.data() + k0;
            predictor_row(
                in,
                {const_cast<double*>(f.h.data()) + k0, const_cast<double*>(f.qn.data()) + k0,
                 const_cast<double*>(f.qt.data()) + k0},
                ratio, h_dry,
                {ph.data() + k0, pq.data() + k0, pt.data() + k0, pu.data() + k0, pv.data() + k0},
                n);
            for (std::ptrdiff_t k = k0; k < k0 + n; ++k) {
                // The loop of Stepper::godunov_predictor before it was vectorised.
                double h = q.h[k] - ratio * (f.h[k + off] - f.h[k]);
                double qn = q.qn[k] - ratio * (f.qn[k + off] - f.qn[k]);
                double qt = q.qt[k] - ratio * (f.qt[k + off] - f.qt[k]);
                const bool state_kept = q.h[k] >= h_dry && !(h >= h_dry);
                if (state_kept) {
                    // Wet in the state, thin in the prediction: the state, not predicted.
                    h = q.h[k];
                    qn = q.qn[k];
                    qt = q.qt[k];
                    ++kept;
                } else if (h <= 0.0) {
                    h = qn = qt = 0.0;
                    ++emptied;
                }
                // The velocity quotients of the values written (NaN for an emptied cell):
                // a kept cell's are the state's, as given.
                const double un = state_kept ? q.un[k] : qn * (1.0 / h);
                const double ut = state_kept ? q.ut[k] : qt * (1.0 / h);
                ASSERT_TRUE((same_bits(un, pu[k]) && same_bits(ut, pv[k])) ||
                            (std::isnan(un) && std::isnan(pu[k])))
                    << "cell " << k;
                ASSERT_TRUE(same_bits(h, ph[k]) && same_bits(qn, pq[k]) && same_bits(qt, pt[k]))
                    << "cell " << k;
            }
        }
    }
    EXPECT_GT(emptied, 100);  // the emptying branch was taken
    EXPECT_GT(kept, 100);     // and the branch that keeps a wet cell wet
}
