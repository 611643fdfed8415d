// The scene fingerprint a resumed run compares (checkpoint_inputs.cpp): equal for equal
// scenes, different when any one value of any field changes in any bit, at any
// position of the word-wise lanes.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "avalanche/io/checkpoint_file.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/dem_frame.hpp"

namespace avalanche {
namespace {

struct Scene {
    Grid grid;
    TerrainFields terrain;
    State initial;
    ActiveBox holding;  // the whole grid unless a test says otherwise
    std::vector<std::uint8_t> sinks;
    std::vector<ProbeLocation> probes;

    explicit Scene(bool on_demand = false) {
        grid.nx = 13;  // the padded rows are not a multiple of the four lanes
        grid.ny = 7;
        grid.dx = grid.dy = 2.0;
        std::vector<double> z(grid.cells());
        for (int j = 0; j < grid.ny; ++j)
            for (int i = 0; i < grid.nx; ++i)
                z[static_cast<std::size_t>(j) * grid.nx + i] = 100.0 - 0.7 * i + 0.01 * i * j;
        DemFrameOptions options;
        options.on_demand = on_demand;
        terrain = dem_terrain(grid, z, 9.81, options);
        initial = State(grid);
        initial.h(3, 2) = 1.5;
        holding = {0, grid.nx, 0, grid.ny};
        sinks.assign(grid.cells(), 0);
        probes.push_back({"p", 5.0, 3.0, 2, 1});
    }
    [[nodiscard]] std::string fingerprint() const {
        return scene_fingerprint(grid, terrain, initial, holding, sinks, probes);
    }
};

double with_bit_flipped(double v, int bit) {
    std::uint64_t w;
    std::memcpy(&w, &v, sizeof w);
    w ^= std::uint64_t{1} << bit;
    std::memcpy(&v, &w, sizeof w);
    return v;
}

TEST(SceneFingerprint, EqualScenesGiveEqualDigests) {
    const Scene a, b;
    EXPECT_EQ(a.fingerprint(), b.fingerprint());
    EXPECT_EQ(a.fingerprint().size(), 16u);
}

TEST(SceneFingerprint, EveryBitOfEveryCellOfAFieldCounts) {
    const Scene reference;
    const std::string base = reference.fingerprint();
    Scene s;
    // Every cell of the elevation (each lane position, ghosts included; not the rows'
    // padding, which holds no cell), the lowest mantissa bit, a middle one and the sign.
    Field2D& z = s.terrain.elevation;
    for (int j = -z.ghosts(); j < z.ny() + z.ghosts(); ++j) {
        for (int i = -z.ghosts(); i < z.nx() + z.ghosts(); ++i) {
            for (const int bit : {0, 31, 63}) {
                double& v = z(i, j);
                const double kept = v;
                v = with_bit_flipped(kept, bit);
                EXPECT_NE(s.fingerprint(), base) << "cell " << i << ", " << j << " bit " << bit;
                v = kept;
            }
        }
    }
    EXPECT_EQ(s.fingerprint(), base);
}

TEST(SceneFingerprint, EachInputCounts) {
    const std::string base = Scene().fingerprint();
    {
        Scene s;
        s.initial.hv(7, 4) = 1e-300;
        EXPECT_NE(s.fingerprint(), base) << "initial state";
    }
    {
        Scene s;
        s.terrain.sx(12, 6) = with_bit_flipped(s.terrain.sx(12, 6), 0);
        EXPECT_NE(s.fingerprint(), base) << "a terrain coefficient";
    }
    {
        Scene s;
        s.sinks[40] = 1;
        EXPECT_NE(s.fingerprint(), base) << "sink mask";
    }
    {
        Scene s;
        s.probes[0].j = 2;
        EXPECT_NE(s.fingerprint(), base) << "monitoring point";
    }
    {
        Scene s;
        // The order of the fields counts.
        std::swap(s.terrain.sx, s.terrain.sy);
        EXPECT_NE(s.fingerprint(), base) << "two fields exchanged";
    }
}

// Of the initial state, the box that holds its material and the cells in it: every bit
// of every cell in the box counts, the box itself counts, and the cells outside it (zero
// by the contract) are not read.
TEST(SceneFingerprint, TheInitialStateCountsInsideItsBox) {
    Scene reference;
    reference.holding = {2, 9, 1, 5};
    const std::string base = reference.fingerprint();
    for (int k = 0; k < 3; ++k)
        for (int j = 1; j < 5; ++j)
            for (int i = 2; i < 9; ++i) {
                Scene s;
                s.holding = reference.holding;
                Field2D& f = k == 0 ? s.initial.h : (k == 1 ? s.initial.hu : s.initial.hv);
                f(i, j) = with_bit_flipped(f(i, j), 0);
                EXPECT_NE(s.fingerprint(), base) << "field " << k << ", cell " << i << ", " << j;
            }
    Scene wider;
    wider.holding = {2, 10, 1, 5};
    EXPECT_NE(wider.fingerprint(), base) << "the box";
    Scene outside;
    outside.holding = reference.holding;
    outside.initial.hu(9, 1) = 2.0;  // beyond the box: a contract broken, not read
    outside.initial.h(0, 0) = 1.0;
    EXPECT_EQ(outside.fingerprint(), base);
    Scene empty;
    empty.holding = {};
    EXPECT_NE(empty.fingerprint(), base);
}

// Terrain made on demand is identified by its elevation: the digest does not depend on
// which tiles a run has made so far, and it differs from the same scene's complete
// terrain (which is hashed field by field).
TEST(SceneFingerprint, TerrainMadeOnDemandCountsByItsElevation) {
    const Scene on_demand(true);
    ASSERT_TRUE(on_demand.terrain.on_demand);
    const std::string base = on_demand.fingerprint();
    on_demand.terrain.ensure(0, 3, 0, 3);
    EXPECT_EQ(on_demand.fingerprint(), base) << "a tile made";
    on_demand.terrain.ensure_everywhere();
    EXPECT_EQ(on_demand.fingerprint(), base) << "every tile made";
    EXPECT_NE(Scene(false).fingerprint(), base);
    Scene s(true);
    s.terrain.elevation(4, 5) = with_bit_flipped(s.terrain.elevation(4, 5), 0);
    EXPECT_NE(s.fingerprint(), base) << "elevation";
}

// The chute's terrain stores one row per field (Field2D::same_in_every_row). Its digest is
// that of its values: the same once a write has given a field every row, different when
// one cell of one row differs from the rest.
TEST(SceneFingerprint, AFieldOfOneRowCountsByItsValues) {
    Scene chute;
    ChuteGeometry c;
    c.slope_deg = 35.0;
    c.length = 26.0;
    c.width = 14.0;
    chute.terrain = chute_terrain(c, chute.grid, 9.81);
    ASSERT_TRUE(chute.terrain.ax.same_in_every_row());
    const std::string base = chute.fingerprint();
    Scene expanded = chute;
    expanded.terrain.ax(4, 5) = std::as_const(chute.terrain.ax)(4, 5);  // a write: every row, same values
    ASSERT_FALSE(expanded.terrain.ax.same_in_every_row());
    EXPECT_EQ(expanded.fingerprint(), base);
    expanded.terrain.ax(4, 5) = with_bit_flipped(expanded.terrain.ax(4, 5), 0);
    EXPECT_NE(expanded.fingerprint(), base) << "one cell of one row";
    Scene other = chute;
    other.terrain.elevation.every_row()[2] += 1e-9;  // every row at once
    EXPECT_NE(other.fingerprint(), base);
}

}  // namespace
}  // namespace avalanche
