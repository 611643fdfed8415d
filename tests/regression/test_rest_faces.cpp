// The kernels of numerics.rest_faces (rest_faces.hpp) on constructed faces whose static
// driving is worked out by hand: c = 10 m/s^2 (k p), tan(delta) = 0.5 and g_n = 10 m/s^2
// (the Coulomb limit 5 m/s^2), cells 1 m wide. The pressure P = c h^2 / 2 of a face's
// cells drives -(P_r - P_l) / ((h_l + h_r) / 2) across it.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "avalanche/numerics/rest_faces.hpp"

namespace avalanche {
namespace {

struct Faces {
    std::vector<double> h_l, h_r, c, an_l, an_r, at, gn, sn, st;
    std::vector<HeldFlag> held_l, held_r;
    std::vector<double> fh, fn, ft;

    void add(double hl, double hr, bool held_left, bool held_right, double anl = 0.0,
             double anr = 0.0, double tangential = 0.0) {
        h_l.push_back(hl);
        h_r.push_back(hr);
        held_l.push_back(held_left ? 1 : 0);
        held_r.push_back(held_right ? 1 : 0);
        an_l.push_back(anl);
        an_r.push_back(anr);
        at.push_back(tangential);
        c.push_back(10.0);
        gn.push_back(10.0);
        sn.push_back(0.0);
        st.push_back(0.0);
        // The scheme's fluxes, recognisable where the kernel leaves them.
        fh.push_back(-1.0);
        fn.push_back(-2.0);
        ft.push_back(-3.0);
    }
    int hold(double tan_delta) {
        const RestFaceRowInput in{h_l.data(),
                                  h_r.data(),
                                  held_l.data(),
                                  held_r.data(),
                                  c.data(),
                                  c.data(),
                                  an_l.data(),
                                  an_r.data(),
                                  at.data(),
                                  at.data(),
                                  gn.data(),
                                  gn.data(),
                                  nullptr,
                                  nullptr,
                                  nullptr,
                                  nullptr};
        return hold_rest_faces_row(in, {1.0, tan_delta, 1e-6}, fh.data(), fn.data(), ft.data(), 0,
                                   static_cast<int>(h_l.size()));
    }
    [[nodiscard]] bool held(std::size_t f) const { return fh[f] == 0.0 && ft[f] == 0.0; }
    [[nodiscard]] bool kept(std::size_t f) const {
        return fh[f] == -1.0 && fn[f] == -2.0 && ft[f] == -3.0;
    }
};

TEST(RestFaceRows, HoldsOnlyFacesBelowTheCoulombLimitBetweenCellsAtRest) {
    Faces f;
    f.add(1.0, 1.2, true, true);   // 0: P 5 | 7.2, drive -2.2 / 1.1 = -2: held
    f.add(1.0, 1.6, true, true);   // 1: P 5 | 12.8, drive -7.8 / 1.3 = -6: beyond the limit
    f.add(1.0, 1.2, true, false);  // 2: the right cell moves (or friction did not hold it)
    f.add(0.4, 0.0, true, false, 0.0, 100.0);    // 3: dry right: drive 0.8 / 0.2 = 4; the dry
                                                 //    cell's slope (100) does not act
    f.add(0.4, 0.0, true, false, 1.5);           // 4: the same with gravity 1.5 along: 5.5
    f.add(0.0, 0.0, true, true);                 // 5: nothing on either side
    f.add(1.0, 1.0, true, true, 3.0, 3.0, 4.5);  // 6: level; gravity (3, 4.5): |.| 5.41
    f.add(1.0, 1.0, true, true, 3.0, 3.0, 3.9);  // 7: level; gravity (3, 3.9): |.| 4.92
    EXPECT_EQ(f.hold(0.5), 3);
    EXPECT_TRUE(f.held(0));
    EXPECT_DOUBLE_EQ(f.fn[0], 0.5 * (5.0 + 7.2));  // the two cells' mean pressure
    EXPECT_TRUE(f.kept(1));
    EXPECT_TRUE(f.kept(2));
    EXPECT_TRUE(f.held(3));
    EXPECT_DOUBLE_EQ(f.fn[3], 0.5 * 0.8);
    EXPECT_TRUE(f.kept(4));
    EXPECT_TRUE(f.kept(5));
    EXPECT_TRUE(f.kept(6));
    EXPECT_TRUE(f.held(7));
}

TEST(RestFaceRows, WithoutFrictionNothingIsHeld) {
    Faces f;
    f.add(1.0, 1.0, true, true);  // level and at rest: zero driving, zero limit
    f.add(1.0, 1.2, true, true);
    EXPECT_EQ(f.hold(0.0), 0);
    EXPECT_TRUE(f.kept(0));
    EXPECT_TRUE(f.kept(1));
}

// In the DEM frame the kernel computes each cell's driving and load from its slopes
// (a = -g grad z / s^2, g_n = g / s; dem_coefficients.hpp) and measures the driving
// along the surface. Two held cells of equal depth (no pressure gradient) on a plane of
// gradient (a, b) along the face's normal and tangent: the along-surface driving is
// g |grad z| / s and the limit tan(delta) g / s, so the face is held exactly where the
// plane is flatter than the friction angle, |grad z| < tan(delta) = 0.5, on x- and
// y-faces alike (a y-face's normal slope is z_y).
TEST(RestFaceRows, TheDemFramesSlopesHoldAPlaneFlatterThanTheFrictionAngle) {
    for (const bool x_faces : {true, false})
        for (const auto& [a, b, held] : {std::tuple{0.45, 0.0, true}, std::tuple{0.55, 0.0, false},
                                         std::tuple{0.0, -0.45, true}, std::tuple{0.0, -0.55, false},
                                         std::tuple{0.3, 0.35, true}, std::tuple{-0.3, 0.42, false}}) {
            Faces f;
            f.add(1.0, 1.0, true, true);
            f.sn[0] = a;
            f.st[0] = b;
            const RestFaceRowInput in{f.h_l.data(), f.h_r.data(), f.held_l.data(), f.held_r.data(),
                                      f.c.data(),   f.c.data(),   nullptr,         nullptr,
                                      nullptr,      nullptr,      nullptr,         nullptr,
                                      f.sn.data(),  f.sn.data(),  f.st.data(),     f.st.data(),
                                      9.81,         x_faces};
            EXPECT_EQ(hold_rest_faces_row(in, {1.0, 0.5, 1e-6}, f.fh.data(), f.fn.data(), f.ft.data(),
                                          0, 1),
                      held ? 1 : 0)
                << (x_faces ? "x" : "y") << "-face, slopes " << a << ", " << b;
            EXPECT_EQ(f.held(0), held);
            if (held) {
                EXPECT_DOUBLE_EQ(f.fn[0], 0.5 * (5.0 + 5.0));  // the cells' pressure
            }
        }
}

// A long row between moving cells with three candidates scattered over it (the kernel
// skips stretches without one): each is tested as alone, every other face kept, at the
// row's first and last faces too, and from an offset start.
TEST(RestFaceRows, ScatteredCandidatesInALongRowAreEachTested) {
    for (const int first : {0, 5}) {
        Faces f;
        for (int k = 0; k < 101; ++k) f.add(1.0, 1.2, false, false);
        for (const int k : {first, 40, 100}) f.held_l[k] = f.held_r[k] = 1;
        f.h_r[40] = 1.6;  // beyond the limit (face 1 of the first test)
        const RestFaceRowInput in{f.h_l.data(), f.h_r.data(), f.held_l.data(), f.held_r.data(),
                                  f.c.data(),   f.c.data(),   f.an_l.data(),   f.an_r.data(),
                                  f.at.data(),  f.at.data(),  f.gn.data(),     f.gn.data(),
                                  nullptr,      nullptr,      nullptr,         nullptr};
        EXPECT_EQ(hold_rest_faces_row(in, {1.0, 0.5, 1e-6}, f.fh.data(), f.fn.data(), f.ft.data(),
                                      first, 101),
                  2);
        for (int k = 0; k < 101; ++k)
            EXPECT_EQ(f.held(static_cast<std::size_t>(k)), k == first || k == 100) << k;
        EXPECT_DOUBLE_EQ(f.fn[100], 0.5 * (5.0 + 7.2));
    }
}

TEST(RestFaceRows, AHeldCellStaysAtRestOnlyIfNoMassCrossedItsFaces) {
    // Three cells of a row (and the rows above and below through the y-faces): cell 0
    // held, all faces quiet; cell 1 held, mass through its upper y-face; cell 2 not held.
    constexpr std::ptrdiff_t kStride = 4;
    const std::vector<HeldFlag> held{1, 1, 0};
    const std::vector<double> fx_h{0.0, 0.0, 0.0, 0.0};
    std::vector<double> fy_h(2 * kStride, 0.0);
    fy_h[kStride + 1] = 1e-9;
    std::vector<double> hu{0.3, 0.3, 0.3}, hv{-0.1, -0.1, -0.1};
    std::vector<HeldFlag> next(3, 7);
    keep_held_at_rest(held.data(), fx_h.data(), fy_h.data(), kStride, hu.data(), hv.data(),
                      next.data(), 0, 3);
    EXPECT_EQ(hu, (std::vector<double>{0.0, 0.3, 0.3}));
    EXPECT_EQ(hv, (std::vector<double>{0.0, -0.1, -0.1}));
    EXPECT_EQ(next, (std::vector<HeldFlag>{1, 0, 0}));
    // Without the next advection's flags (a friction stage comes between), the same.
    hu.assign(3, 0.3);
    hv.assign(3, -0.1);
    keep_held_at_rest(held.data(), fx_h.data(), fy_h.data(), kStride, hu.data(), hv.data(), nullptr,
                      0, 3);
    EXPECT_EQ(hu, (std::vector<double>{0.0, 0.3, 0.3}));
    EXPECT_EQ(hv, (std::vector<double>{0.0, -0.1, -0.1}));
}

TEST(RestFaceRows, TheFrictionStageHoldsTheCellsWithZeroMomentum) {
    const std::vector<double> h{1.0, 1.0, 1e-9, 0.0, 1.0};
    const std::vector<double> hu{0.0, 0.1, 0.0, 0.0, -0.0};
    const std::vector<double> hv{0.0, 0.0, 0.0, 0.0, 0.0};
    std::vector<HeldFlag> held(5, 7);
    held_at_rest_row(h.data(), hu.data(), hv.data(), 1e-6, held.data(), 0, 5);
    // Moving, thinner than h_min and dry cells are not held; -0 is zero momentum.
    EXPECT_EQ(held, (std::vector<HeldFlag>{1, 0, 0, 0, 1}));
}

}  // namespace
}  // namespace avalanche
