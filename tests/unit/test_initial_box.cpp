// The box of the released cells (state_at_rest): every cell of the initial state outside
// it is zero, so what reads the initial state -- the mass balance, the thin-layer depth,
// the release's top, the first active box -- reads only that box, with the whole grid's
// results to the bit, and a small release on a large grid leaves the rest of the state's
// memory unread (on an ASTER-size tile those reads were 0.5 s of page faults a run).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "avalanche/core/simulation.hpp"
#include "avalanche/output/runout.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"
#include "support/resident_memory.hpp"
#include "support/same_bits.hpp"

using namespace avalanche;

namespace {

constexpr double kG = 9.81;

// A plane with a bump, so that the cells' normal thicknesses and elevations differ.
TerrainFields bumpy_plane(const Grid& g) {
    std::vector<double> z(g.cells());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double x = g.x_center(i), y = g.y_center(j);
            z[static_cast<std::size_t>(j) * g.nx + i] = 0.3 * x + 0.1 * y + 5.0 * std::sin(0.05 * x * y);
        }
    return dem_terrain(g, z, kG);
}

using test::same_bits;

}  // namespace

TEST(InitialBox, StateAtRestGivesTheBoxOfTheReleasedCells) {
    const Grid g{40, 30, 5.0, 5.0};
    const TerrainFields t = bumpy_plane(g);
    Field2D thickness(g.nx, g.ny, kGhostLayers);
    thickness(5, 7) = 1.0;
    thickness(12, 20) = 0.25;
    thickness(8, 9) = 2.0;
    ActiveBox box{-1, -1, -1, -1};
    const State s = state_at_rest(g, thickness, t, &box);
    EXPECT_EQ(box.i0, 5);
    EXPECT_EQ(box.i1, 13);
    EXPECT_EQ(box.j0, 7);
    EXPECT_EQ(box.j1, 21);
    EXPECT_GT(s.h(12, 20), 0.0);
    ActiveBox none{1, 2, 3, 4};
    (void)state_at_rest(g, Field2D(g.nx, g.ny, kGhostLayers), t, &none);
    EXPECT_TRUE(none.empty());
}

// A state set cell by cell on a terrain made on demand, whose tiles no one has made yet:
// the automatic thin-layer depth is still h_min_relative x the deepest bed-normal
// thickness, not h_min_relative alone (the normal thickness of a tile not made reads 0).
TEST(InitialBox, AutomaticThinLayerDepthMakesTheTerrainItReads) {
    const Grid g{40, 30, 5.0, 5.0};
    const TerrainFields made = bumpy_plane(g), fresh = bumpy_plane(g);
    made.ensure_everywhere();
    State s(g);
    s.h(30, 20) = 2.0;
    s.h(31, 20) = 1.0;
    NumericsParams n;
    const double expected = n.h_min_relative * 2.0 * made.normal_thickness(30, 20);
    EXPECT_LT(made.normal_thickness(30, 20), 1.0);  // a slope: thinner than vertical
    EXPECT_TRUE(same_bits(effective_h_min(n, s, fresh), expected));
    EXPECT_TRUE(
        same_bits(effective_h_min(n, s, bumpy_plane(g), ActiveBox{30, 32, 20, 21}), expected));

    // It makes the terrain of the released cells only, not of the whole grid it searches:
    // a release in one corner of a grid of 5 x 5 tiles makes one tile (and its 3 x 3 halo
    // of curvature cells stays inside it).
    const Grid large{5 * TerrainTiles::kTileCells, 5 * TerrainTiles::kTileCells, 5.0, 5.0};
    const TerrainFields untouched = bumpy_plane(large), whole = bumpy_plane(large);
    whole.ensure_everywhere();
    State corner(large);
    corner.h(10, 10) = 1.0;
    EXPECT_TRUE(same_bits(effective_h_min(n, corner, untouched),
                          n.h_min_relative * whole.normal_thickness(10, 10)));
    ASSERT_NE(untouched.on_demand, nullptr);
    EXPECT_EQ(untouched.on_demand->tiles_made(), 1u);
}

TEST(InitialBox, ItsReadersGiveTheWholeGridsValues) {
    const Grid g{40, 30, 5.0, 5.0};
    const TerrainFields t = bumpy_plane(g);
    Field2D thickness(g.nx, g.ny, kGhostLayers);
    for (int j = 9; j < 17; ++j)
        for (int i = 11; i < 23; ++i) thickness(i, j) = 0.5 + 0.01 * (i * j % 7);
    thickness(14, 12) = 1e-6;  // thinner than the threshold of the release's top
    ActiveBox box;
    const State s = state_at_rest(g, thickness, t, &box);
    const ActiveBox whole{0, g.nx, 0, g.ny};
    EXPECT_TRUE(same_bits(total_volume(s, g, box), total_volume(s, g)));
    EXPECT_GT(total_volume(s, g), 0.0);
    NumericsParams n;
    EXPECT_TRUE(same_bits(effective_h_min(n, s, t, box), effective_h_min(n, s, t)));
    const ReleaseTop a = release_top(g, t, s, 0.01, box), b = release_top(g, t, s, 0.01);
    EXPECT_EQ(a.i, b.i);
    EXPECT_EQ(a.j, b.j);
    EXPECT_GE(a.i, 0);
    const double h_min = effective_h_min(n, s, t);
    const Simulation boxed(g, t, MaterialParams{}, n, s, h_min, box);
    const Simulation searched(g, t, MaterialParams{}, n, s, h_min, whole);
    const ActiveBox& x = boxed.stepper().active_box();
    const ActiveBox& y = searched.stepper().active_box();
    EXPECT_EQ(x.i0, y.i0);
    EXPECT_EQ(x.i1, y.i1);
    EXPECT_EQ(x.j0, y.j0);
    EXPECT_EQ(x.j1, y.j1);
    EXPECT_FALSE(x.empty());
}

// Read whole, the three untouched 16 MB fields of this state fault about 12 000 pages in
// (each read maps a page, the shared zero page or one of its own); in the box, a few.
TEST(InitialBox, ASmallReleaseOnALargeGridIsReadOnlyInItsBox) {
    if (test::minor_page_faults() < 0) GTEST_SKIP() << "no getrusage page-fault counts";
    const Grid g{2000, 1000, 10.0, 10.0};
    const TerrainFields t = bumpy_plane(g);
    ActiveBox box;
    Field2D thickness(g.nx, g.ny, kGhostLayers);
    for (int j = 500; j < 510; ++j)
        for (int i = 700; i < 712; ++i) thickness(i, j) = 1.0;
    State s = state_at_rest(g, thickness, t, &box);
    NumericsParams n;
    const long before = test::minor_page_faults();
    const double volume = total_volume(s, g, box);
    const double h_min = effective_h_min(n, s, t, box);
    const ReleaseTop top = release_top(g, t, s, 0.01, box);
    const Simulation sim(g, t, MaterialParams{}, n, std::move(s), h_min, box);  // a copy writes
    const long faults = test::minor_page_faults() - before;
    EXPECT_LT(faults, 1000) << "the initial state was read beyond the release's box";
    EXPECT_GT(volume, 0.0);
    EXPECT_GE(top.i, 700);
    EXPECT_FALSE(sim.stepper().active_box().empty());
}

// An analytic shape's field is zero outside the cells over its extent (release_cells), so
// its state at rest is searched there only: the same state and box as the whole grid's.
TEST(InitialBox, AShapesStateIsSearchedInTheCellsOverItsExtent) {
    const Grid g{60, 45, 2.0, 2.0, 100.0, 50.0};
    const TerrainFields t = bumpy_plane(g);
    const ReleaseShape shapes[] = {CapRelease{{150.0, 90.0}, 7.0},
                                   ParaboloidRelease{{110.0, 60.0}, 15.0, 2.0},  // over the corner
                                   BoxRelease{{181.0, 230.0}, {120.0, 139.0}, 1.5}};
    for (const ReleaseShape& shape : shapes) {
        const Field2D f = rasterize_release(shape, g);
        const ActiveBox cells = release_cells(shape, g);
        long outside = 0, inside = 0;
        for (int j = -kGhostLayers; j < g.ny + kGhostLayers; ++j)
            for (int i = -kGhostLayers; i < g.nx + kGhostLayers; ++i) {
                const bool in = i >= cells.i0 && i < cells.i1 && j >= cells.j0 && j < cells.j1;
                (in ? inside : outside) += f(i, j) != 0.0;
            }
        EXPECT_EQ(outside, 0);
        EXPECT_GT(inside, 0);
        ActiveBox a, b;
        const State whole = state_at_rest(g, f, t, &a);
        const State searched = state_at_rest(g, f, t, cells, &b);
        EXPECT_TRUE(same_bits(whole.h, searched.h));
        EXPECT_EQ(a.i0, b.i0);
        EXPECT_EQ(a.i1, b.i1);
        EXPECT_EQ(a.j0, b.j0);
        EXPECT_EQ(a.j1, b.j1);
    }
}
