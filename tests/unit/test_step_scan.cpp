// The state scan after every step (scan_state, core/simulation.cpp): one pass that
// checks the state, sums the kinetic energy and tests for rest, on several threads
// when the box is large. Its results must not depend on the thread count: the fault
// report names the row-major first bad cell, and the kinetic energy decides when a
// run stops, so 1 and 2 threads must give the same cell and the same bits.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "avalanche/core/error.hpp"
#include "avalanche/core/simulation.hpp"
#include "support/analytic_harness.hpp"

using namespace avalanche;
using avalanche::analytic::ScopedThreads;

namespace {

// 400 x 300 cells: the box below holds 390 x 290 = 113 100 cells, far above the
// threshold (20 000) from which the scan runs on several threads.
Grid scan_grid() { return Grid{400, 300, 2.0, 3.0, 100.0, 200.0}; }
constexpr ActiveBox kBox{5, 395, 4, 294};

// A moving layer with round-off-rich values (and some dry cells, which carry no
// kinetic energy), reproducible without <random>'s implementation-defined engines.
State flowing_state(const Grid& g) {
    State s(g);
    std::uint64_t x = 88172645463325252ULL;
    const auto next = [&x]() {  // xorshift64, uniform in [0, 1)
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        return static_cast<double>(x >> 11) * 0x1.0p-53;
    };
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double h = next() < 0.1 ? 0.0 : 0.01 + 3.0 * next();
            s.h(i, j) = h;
            s.hu(i, j) = h * (20.0 * next() - 5.0);
            s.hv(i, j) = h * (6.0 * next() - 3.0);
        }
    return s;
}

struct BadCell {
    int i = -1, j = -1;
    std::string what;
};

BadCell scan_for_fault(const State& s, const Grid& g, int threads) {
    const ScopedThreads team(threads);
    try {
        (void)scan_state(s, g, kBox, 1.5);
    } catch (const NumericalError& e) {
        return {e.i(), e.j(), e.what()};
    }
    return {};
}

}  // namespace

TEST(StepScan, NamesTheRowMajorFirstBadCellOnAnyThreadCount) {
    const Grid g = scan_grid();
    State s = flowing_state(g);
    // Outside the box: not scanned (the stepper keeps everything there dry).
    s.h(1, 1) = std::numeric_limits<double>::quiet_NaN();
    // The first bad cell is (200, 100), in the first thread's half of the rows; the
    // same row holds a later one, the next row one further left, and the second
    // thread's half two more.
    s.hv(200, 100) = std::numeric_limits<double>::infinity();
    s.h(300, 100) = -1e-3;
    s.h(10, 101) = std::numeric_limits<double>::quiet_NaN();
    s.h(20, 200) = -2.0;
    s.hu(5, 280) = std::numeric_limits<double>::quiet_NaN();
    for (const int threads : {1, 2}) {
        SCOPED_TRACE(threads);
        const BadCell bad = scan_for_fault(s, g, threads);
        EXPECT_EQ(bad.i, 200);
        EXPECT_EQ(bad.j, 100);
        EXPECT_EQ(
            bad.what.rfind("non-finite value (NaN or Inf) in the state at cell (i=200, j=100), "
                           "x=501.000000 m, y=501.500000 m, t=1.500000 s",
                           0),
            0u)
            << bad.what;
    }
    // A negative depth is named as such (a non-finite value takes precedence in a cell
    // that has both).
    s.hv(200, 100) = 0.0;
    for (const int threads : {1, 2}) {
        SCOPED_TRACE(threads);
        const BadCell bad = scan_for_fault(s, g, threads);
        EXPECT_EQ(bad.i, 300);
        EXPECT_EQ(bad.j, 100);
        EXPECT_EQ(bad.what.rfind("negative depth at cell (i=300, j=100)", 0), 0u) << bad.what;
    }
    s.hu(300, 100) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(scan_for_fault(s, g, 2).what.rfind("non-finite value", 0), 0u);
}

namespace {

// A state on which the order of summation shows in the double result: one fast deep
// cell first in the box, then a creeping film whose cells each hold about a third of
// a long double ulp of that cell's energy. Added one by one after it, every film cell
// rounds away; a sum that regrouped the cells by thread would keep ~10 double ulps of
// them.
State order_sensitive_state(const Grid& g) {
    State s(g);
    for (int j = kBox.j0; j < kBox.j1; ++j)
        for (int i = kBox.i0; i < kBox.i1; ++i) {
            s.h(i, j) = 0.01;
            s.hu(i, j) = 5e-9;  // 0.5 hu^2 / h = 1.25e-15; ulp(5e4) = 2^-48 = 3.6e-15
        }
    s.h(kBox.i0, kBox.j0) = 10.0;
    s.hu(kBox.i0, kBox.j0) = 1000.0;  // 0.5 hu^2 / h = 5e4
    return s;
}

StepScan scan_on(int threads, const State& s, const Grid& g) {
    const ScopedThreads team(threads);
    return scan_state(s, g, kBox, 0.0);
}

}  // namespace

TEST(StepScan, KineticEnergyIsBitwiseTheSameOnOneAndTwoThreads) {
    const Grid g = scan_grid();
    for (const State& s : {flowing_state(g), order_sensitive_state(g)}) {
        const StepScan one = scan_on(1, s, g);
        const StepScan two = scan_on(2, s, g);
        EXPECT_EQ(std::bit_cast<std::uint64_t>(one.kinetic_energy),
                  std::bit_cast<std::uint64_t>(two.kinetic_energy));
        EXPECT_FALSE(one.at_rest);
        EXPECT_FALSE(two.at_rest);

        // The value: sum of h |u|^2 / 2 dA over the wet cells of the box.
        long double reference = 0.0L;
        for (int j = kBox.j0; j < kBox.j1; ++j)
            for (int i = kBox.i0; i < kBox.i1; ++i)
                if (s.h(i, j) > 0.0)
                    reference +=
                        0.5L * (s.hu(i, j) * s.hu(i, j) + s.hv(i, j) * s.hv(i, j)) / s.h(i, j);
        reference *= g.cell_area();
        EXPECT_NEAR(one.kinetic_energy, static_cast<double>(reference), 1e-14 * reference);
    }
}

TEST(StepScan, RestNeedsEveryMomentumExactlyZero) {
    const Grid g = scan_grid();
    State s(g);
    s.h.fill(1.0);
    // Momentum outside the box does not count.
    s.hu(0, 0) = 1.0;
    for (const int threads : {1, 2}) {
        SCOPED_TRACE(threads);
        const ScopedThreads team(threads);
        StepScan r = scan_state(s, g, kBox, 0.0);
        EXPECT_TRUE(r.at_rest);
        EXPECT_EQ(r.kinetic_energy, 0.0);
        s.hv(394, 293) = 1e-300;  // the box's last cell
        r = scan_state(s, g, kBox, 0.0);
        EXPECT_FALSE(r.at_rest);
        s.hv(394, 293) = 0.0;
    }
    const StepScan empty = scan_state(s, g, ActiveBox{}, 0.0);
    EXPECT_TRUE(empty.at_rest);
    EXPECT_EQ(empty.kinetic_energy, 0.0);
}
