// A batch's scenarios run from copies of one prepared scene's initial state
// (PreparedScene::initial_copy): the copy must be the state to the bit, ghost cells
// included, and with the release's box known it writes only that box, so that a small
// release on a large DEM does not write 24 bytes a cell for every scenario.
#include <gtest/gtest.h>

#include <vector>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"
#include "support/resident_memory.hpp"
#include "support/same_bits.hpp"

namespace avalanche {
namespace {

using test::same_bits;

PreparedScene small_release_on(const Grid& g) {
    PreparedScene p;
    p.frame = Frame::dem;
    p.grid = g;
    std::vector<double> z(g.cells());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) z[static_cast<std::size_t>(j) * g.nx + i] = 0.2 * i + 0.05 * j;
    p.terrain = dem_terrain(g, z, 9.81);
    // 15 x 12 cells from 45 % and 40 % of the grid's sides.
    const int i0 = g.nx * 9 / 20, j0 = g.ny * 2 / 5;
    Field2D thickness(g.nx, g.ny, kGhostLayers);
    for (int j = j0; j < j0 + 12; ++j)
        for (int i = i0; i < i0 + 15; ++i) thickness(i, j) = 1.0 + 0.01 * i;
    p.initial_box.emplace();
    p.initial = state_at_rest(g, thickness, p.terrain, &*p.initial_box);
    p.initial.hu(i0 + 5, j0 + 5) = 0.5;  // momenta count too
    p.initial.hv(i0 + 6, j0 + 11) = -0.25;
    return p;
}

TEST(InitialCopy, IsTheStateToTheBitAndWritesOnlyTheReleasesBox) {
    if (test::minor_page_faults() < 0) GTEST_SKIP() << "no getrusage page-fault counts";
    const PreparedScene p = small_release_on(Grid{2000, 1000, 10.0, 10.0});  // 16 MB a field
    const long before = test::minor_page_faults();
    const State copy = p.initial_copy();
    const long faults = test::minor_page_faults() - before;
    EXPECT_LT(faults, 500) << "the whole state was written (about 12 000 pages)";
    EXPECT_TRUE(same_bits(copy.h, p.initial.h));
    EXPECT_TRUE(same_bits(copy.hu, p.initial.hu));
    EXPECT_TRUE(same_bits(copy.hv, p.initial.hv));
    EXPECT_GT(copy.h(914, 411), 0.0);

    // Without a box (a scene built by hand), the whole state, ghost cells included.
    PreparedScene unknown = small_release_on(Grid{50, 40, 10.0, 10.0});
    unknown.initial_box.reset();
    unknown.initial.h(-2, -1) = 3.0;
    const State whole = unknown.initial_copy();
    EXPECT_TRUE(same_bits(whole.h, unknown.initial.h));
    EXPECT_EQ(whole.h(-2, -1), 3.0);
}

}  // namespace
}  // namespace avalanche
