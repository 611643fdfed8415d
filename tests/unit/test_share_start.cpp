// share_start (active_box.hpp): where each thread's strips of an advection begin.
#include <gtest/gtest.h>

#include <vector>

#include "avalanche/numerics/active_box.hpp"

namespace avalanche {
namespace {

// Strips of 16, 24, 8 cells (before = 0, 16, 40, 48): half the work is 24 cells, 8 past
// the first boundary and 16 before the second, so the second thread starts at strip 1
// (the first boundary at or beyond 24 would give the first thread 40 of the 48 cells).
TEST(ShareStart, TheBoundaryNearestToTheShare) {
    const std::vector<std::size_t> before{0, 16, 40, 48};
    EXPECT_EQ(share_start(before, 0, 2), 0);
    EXPECT_EQ(share_start(before, 1, 2), 1);
    EXPECT_EQ(share_start(before, 2, 2), 3);
    // A share on a boundary starts there; halfway between two, at the later one.
    const std::vector<std::size_t> equal{0, 10, 20, 30, 40};
    EXPECT_EQ(share_start(equal, 1, 2), 2);  // 20: boundary 2
    EXPECT_EQ(share_start(equal, 1, 4), 1);  // 10: boundary 1
    EXPECT_EQ(share_start(equal, 1, 8), 1);  // 5: halfway between 0 and 10
    const std::vector<std::size_t> near_later{0, 10, 30};
    EXPECT_EQ(share_start(near_later, 1, 2), 1);  // 15: 5 past 10, 15 before 30
    const std::vector<std::size_t> near_earlier{0, 20, 30};
    EXPECT_EQ(share_start(near_earlier, 1, 2), 1);  // 15: 15 past 0, 5 before 20
}

// Every thread's share starts where the previous one's ends, in order, and covers the
// strips once: thread t takes [share_start(t), share_start(t + 1)).
TEST(ShareStart, SharesAreOrderedAndCoverEveryStrip) {
    std::vector<std::size_t> before{0};
    for (std::size_t k = 0; k < 37; ++k) before.push_back(before.back() + 100 + (k * 37) % 91);
    for (int n = 1; n <= 8; ++n) {
        EXPECT_EQ(share_start(before, 0, n), 0) << n;
        EXPECT_EQ(share_start(before, n, n), 37) << n;
        for (int t = 0; t < n; ++t) EXPECT_LE(share_start(before, t, n), share_start(before, t + 1, n)) << n;
    }
    // An empty list: every thread starts at its end.
    const std::vector<std::size_t> none{0};
    EXPECT_EQ(share_start(none, 0, 2), 0);
    EXPECT_EQ(share_start(none, 1, 2), 0);
}

}  // namespace
}  // namespace avalanche
