// Fields the same in every row (Field2D::same_in_every_row): the chute's terrain, which
// varies only down the slope, stores one row per field. Every row, ghost rows included,
// reads that row; a write that could make the rows differ first gives the field every
// row; and the solver, which reads the terrain through const references, runs the chute
// without ever doing so.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "avalanche/core/field.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/release.hpp"

using namespace avalanche;

TEST(FieldSameInEveryRow, EveryRowReadsTheOneStored) {
    Field2D f = Field2D::same_in_every_row(7, 5, 2, 0.5);
    EXPECT_TRUE(f.same_in_every_row());
    // One row: 7 cells, 2 x 2 ghosts, column 0 on a cache line and the row padded to one.
    EXPECT_EQ(std::as_const(f).raw().size(), static_cast<std::size_t>(f.stride()));
    EXPECT_EQ(f.stride(), 24);
    double* row = f.every_row();
    for (int i = 0; i < 7; ++i) row[i] = 10.0 + i;
    f.extend_to_ghosts();
    EXPECT_TRUE(f.same_in_every_row()) << "the ghost extension wrote every row";
    const Field2D& c = f;
    for (int j = -2; j < 7; ++j) {
        for (int i = 0; i < 7; ++i) ASSERT_EQ(c(i, j), 10.0 + i) << i << ", " << j;
        EXPECT_EQ(c(-2, j), 10.0);
        EXPECT_EQ(c(8, j), 16.0);
        EXPECT_EQ(c.row(j)[3], 13.0);
    }
    // A copy keeps the one row; so does an assignment and a fill.
    Field2D copy = f;
    EXPECT_TRUE(copy.same_in_every_row());
    EXPECT_EQ(std::as_const(copy)(4, 6), 14.0);
    Field2D assigned(7, 5, 2);
    assigned = f;
    EXPECT_TRUE(assigned.same_in_every_row());
    EXPECT_EQ(std::as_const(assigned)(4, -2), 14.0);
    copy.fill(3.0);
    EXPECT_TRUE(copy.same_in_every_row());
    EXPECT_EQ(std::as_const(copy)(6, 4), 3.0);
    // An ordinary field is not one.
    EXPECT_FALSE(Field2D(7, 5, 2).same_in_every_row());
    EXPECT_FALSE(Field2D().same_in_every_row());
}

TEST(FieldSameInEveryRow, AWriteGivesItEveryRowAndKeepsTheValues) {
    Field2D f = Field2D::same_in_every_row(6, 4, 2, 2.0);
    f.every_row()[1] = 5.0;
    f.extend_to_ghosts();
    f(1, 2) = -1.0;  // only row 2 changes
    EXPECT_FALSE(f.same_in_every_row());
    EXPECT_EQ(f.raw().size(), static_cast<std::size_t>(f.stride()) * 8u);
    const Field2D& c = f;
    for (int j = -2; j < 6; ++j) {
        EXPECT_EQ(c(1, j), j == 2 ? -1.0 : 5.0) << j;
        EXPECT_EQ(c(0, j), 2.0);
        EXPECT_EQ(c(-2, j), 2.0);
    }
    // The same through row(j) and raw().
    Field2D g = Field2D::same_in_every_row(6, 4, 2, 2.0);
    g.row(-1)[0] = 7.0;
    EXPECT_EQ(std::as_const(g)(0, -1), 7.0);
    EXPECT_EQ(std::as_const(g)(0, 0), 2.0);
    Field2D h = Field2D::same_in_every_row(6, 4, 2, 2.0);
    h.raw()[h.index(3, 3)] = 9.0;
    EXPECT_EQ(std::as_const(h)(3, 3), 9.0);
    EXPECT_EQ(std::as_const(h)(3, 2), 2.0);
}

namespace {
ChuteGeometry chute_with_transition() {
    ChuteGeometry c;
    c.slope_deg = 40.0;
    c.runout_slope_deg = 0.0;
    c.length = 30.0;
    c.width = 8.0;
    c.transition_start = 12.0;
    c.transition_end = 20.0;
    return c;
}

// Every field of t the chute frame has: the terrain's own list of the derived fields
// (kDerivedTerrainFields, without the slopes a bed-fitted frame leaves empty) and the
// elevation.
std::vector<const Field2D*> chute_fields(const TerrainFields& t) {
    std::vector<const Field2D*> fields;
    for (Field2D TerrainFields::*f : kDerivedTerrainFields)
        if (!(t.*f).empty()) fields.push_back(&(t.*f));
    fields.push_back(&t.elevation);
    return fields;
}
}  // namespace

// The chute's terrain in one row per field holds, at every cell and ghost cell, the values
// of the frame's definition (terrain.hpp): a_x = g sin(zeta), p = g_n = g cos(zeta), a_y = 0,
// c_xx = -dzeta/dx only, bed-normal thickness factor 1.
TEST(FieldSameInEveryRow, TheChuteTerrainIsOneRowPerFieldWithTheFramesValues) {
    const ChuteGeometry c = chute_with_transition();
    const Grid grid = chute_grid(c, 0.5);
    const double g = 9.81;
    const TerrainFields t = chute_terrain(c, grid, g);
    ASSERT_TRUE(t.has_curvature);
    ASSERT_EQ(chute_fields(t).size(), 10u);
    for (const Field2D* f : chute_fields(t)) EXPECT_TRUE(f->same_in_every_row());
    const int ng = t.ax.ghosts();
    for (int j = -ng; j < grid.ny + ng; ++j) {
        for (int i = -ng; i < grid.nx + ng; ++i) {
            const int ii = std::clamp(i, 0, grid.nx - 1);  // ghosts: zero gradient
            const double x = grid.x_center(ii), zeta = c.inclination(x);
            ASSERT_EQ(t.ax(i, j), g * std::sin(zeta)) << i << ", " << j;
            ASSERT_EQ(t.px(i, j), g * std::cos(zeta));
            ASSERT_EQ(t.py(i, j), g * std::cos(zeta));
            ASSERT_EQ(t.gn(i, j), g * std::cos(zeta));
            ASSERT_EQ(t.ay(i, j), 0.0);
            ASSERT_EQ(t.cxx(i, j), c.curvature(x));
            ASSERT_EQ(t.cxy(i, j), 0.0);
            ASSERT_EQ(t.cyy(i, j), 0.0);
            ASSERT_EQ(t.normal_thickness(i, j), 1.0);
            ASSERT_EQ(t.elevation(i, j), c.elevation(x));
        }
    }
}

// A run down the chute to its stop, through the transition's curvature, reads the
// terrain but never writes it: its fields are still one row each afterwards (a hidden
// write would give them every row, 80 bytes per cell, docs/performance.md).
TEST(FieldSameInEveryRow, AChuteRunLeavesTheTerrainOneRowPerField) {
    const ChuteGeometry c = chute_with_transition();
    const Grid grid = chute_grid(c, 0.5);
    const TerrainFields t = chute_terrain(c, grid, 9.81);
    const State initial =
        state_at_rest(grid, rasterize_release(ParaboloidRelease{{5.0, 4.0}, 2.0, 1.0}, grid), t);
    MaterialParams m;
    m.phi_deg = 30.0;
    m.delta_deg = 24.0;
    NumericsParams n;
    n.t_end = 30.0;
    Simulation sim(grid, t, m, n, initial, effective_h_min(n, initial, t));
    const RunStatistics stats = sim.run();
    EXPECT_NE(stats.end_reason, EndReason::end_time) << "the flow should stop in the runout";
    EXPECT_GT(stats.steps, 10u);
    ASSERT_EQ(chute_fields(t).size(), 10u);
    for (const Field2D* f : chute_fields(t)) EXPECT_TRUE(f->same_in_every_row());
}
