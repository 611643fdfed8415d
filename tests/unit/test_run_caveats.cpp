// The caveats of a run (output/run_caveats.hpp): which reached cells lie where the
// terrain ends, and when a run's maps are said to understate the hazard.
#include <gtest/gtest.h>

#include <vector>

#include "avalanche/output/run_caveats.hpp"

namespace avalanche {
namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// 6 x 4 cells, threshold 0.01 m; k = j * 6 + i.
TEST(EdgeContact, CountsReachedCellsOnEachSideAndBesideTheNoDataArea) {
    const Grid g{6, 4, 10.0, 10.0};
    std::vector<double> depth(g.cells(), 0.0);
    auto at = [&](int i, int j) -> double& { return depth[static_cast<std::size_t>(j) * 6 + i]; };
    at(5, 1) = 0.02;   // east side
    at(5, 3) = 0.5;    // the north-east corner: east and north
    at(0, 0) = 0.009;  // below the threshold: not reached
    at(0, 2) = 0.01;   // exactly the threshold: reached, west side
    at(2, 2) = 1.0;    // inside, beside the sink cell (3, 2)
    at(2, 1) = 1.0;    // inside, diagonal to the sink only: not beside it
    std::vector<std::uint8_t> sinks(g.cells(), 0);
    sinks[2 * 6 + 3] = 1;

    const EdgeContact c = edge_contact(g, depth, 0.01, sinks);
    EXPECT_EQ(c.low_i, 1);
    EXPECT_EQ(c.high_i, 2);
    EXPECT_EQ(c.low_j, 0);
    EXPECT_EQ(c.high_j, 1);
    EXPECT_EQ(c.beside_no_data, 1);
    EXPECT_TRUE(c.any());

    // Without the sink mask the interior cell does not count; a sink cell reached itself does.
    EXPECT_EQ(edge_contact(g, depth, 0.01, {}).beside_no_data, 0);
    at(3, 2) = 0.3;
    EXPECT_EQ(edge_contact(g, depth, 0.01, sinks).beside_no_data, 2);

    // Nothing reached at the edges: no contact.
    std::vector<double> inside(g.cells(), 0.0);
    inside[1 * 6 + 2] = 5.0;
    EXPECT_FALSE(edge_contact(g, inside, 0.01, {}).any());
}

// With the box the maps' cells were reached in (HazardMaps::reach_box) only that box is
// read: where it holds every reached cell the counts are those of the whole grid, and a
// cell outside it is not looked at (here one that the box wrongly leaves out).
TEST(EdgeContact, ReadsOnlyInsideTheReachBox) {
    const Grid g{6, 4, 10.0, 10.0};
    std::vector<double> depth(g.cells(), 0.0);
    auto at = [&](int i, int j) -> double& { return depth[static_cast<std::size_t>(j) * 6 + i]; };
    at(5, 1) = 0.02;
    at(5, 3) = 0.5;
    at(0, 2) = 0.01;
    at(2, 2) = 1.0;
    at(3, 2) = 0.3;  // a sink reached
    std::vector<std::uint8_t> sinks(g.cells(), 0);
    sinks[2 * 6 + 3] = 1;
    const EdgeContact whole = edge_contact(g, depth, 0.01, sinks);
    const EdgeContact boxed = edge_contact(g, depth, 0.01, sinks, ActiveBox{0, 6, 1, 4});
    EXPECT_EQ(boxed.low_i, whole.low_i);
    EXPECT_EQ(boxed.high_i, whole.high_i);
    EXPECT_EQ(boxed.low_j, whole.low_j);
    EXPECT_EQ(boxed.high_j, whole.high_j);
    EXPECT_EQ(boxed.beside_no_data, whole.beside_no_data);
    EXPECT_EQ(whole.low_i, 1);
    EXPECT_EQ(whole.beside_no_data, 2);
    const EdgeContact east = edge_contact(g, depth, 0.01, sinks, ActiveBox{1, 6, 0, 4});
    EXPECT_EQ(east.low_i, 0);
    EXPECT_EQ(east.high_i, 2);
    EXPECT_EQ(east.high_j, 1);
    EXPECT_EQ(east.beside_no_data, 2);
    EXPECT_FALSE(edge_contact(g, depth, 0.01, sinks, ActiveBox{}).any());
}

RunStatistics stopped_run() {
    RunStatistics st;
    st.end_reason = EndReason::stopped_kinetic_energy;
    st.simulated_time = 86.3;
    st.released_volume = 1000.0;
    st.final_volume = 1000.0;
    st.max_kinetic_energy = 1e6;
    st.final_kinetic_energy = 50.0;
    return st;
}

TEST(RunCaveats, NoneForARunThatStoppedInsideTheGrid) {
    const RunStatistics st = stopped_run();
    const NumericsParams n;
    EXPECT_TRUE(run_caveats({st, EdgeContact{}, Frame::dem, n}).empty());
    // Films thinner than h_threshold leaving under a hundredth of the release: none.
    RunStatistics films = st;
    films.outflow_volume = 9.0;
    films.final_volume = 991.0;
    EXPECT_TRUE(run_caveats({films, EdgeContact{}, Frame::dem, n}).empty());
}

TEST(RunCaveats, ReachedEdgeNamesTheSidesAndTheVolumeThatLeft) {
    RunStatistics st = stopped_run();
    st.outflow_volume = 207.0;
    st.final_volume = 793.0;
    EdgeContact e;
    e.high_i = 2;
    e.high_j = 1;
    e.beside_no_data = 5;
    const NumericsParams n;
    const auto c = run_caveats({st, e, Frame::dem, n});
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].code, "reached_edge");
    EXPECT_TRUE(has(c[0].message, "the east side (2 cells), the north side (1 cell) and the DEM's no-data area (5 cells)"))
        << c[0].message;
    EXPECT_TRUE(has(c[0].message, "207 m3 (20.7 % of the release) left the grid")) << c[0].message;
    EXPECT_TRUE(has(c[0].message, "extend the DEM")) << c[0].message;

    // The chute frame names its ends; walls hold the flow instead of letting it leave.
    RunStatistics held = stopped_run();
    NumericsParams walls;
    walls.boundary = Boundary::wall;
    EdgeContact lower;
    lower.high_i = 3;
    const auto w = run_caveats({held, lower, Frame::chute, walls});
    ASSERT_EQ(w.size(), 1u);
    EXPECT_TRUE(has(w[0].message, "the lower end (3 cells)")) << w[0].message;
    EXPECT_TRUE(has(w[0].message, "walls")) << w[0].message;
    EXPECT_FALSE(has(w[0].message, "left the grid")) << w[0].message;

    // A hundredth of the release gone in films no edge cell recorded: still a caveat,
    // which says that nothing reached counted there.
    RunStatistics films = stopped_run();
    films.outflow_volume = 10.0;
    const auto f = run_caveats({films, EdgeContact{}, Frame::dem, n, 0.01});
    ASSERT_EQ(f.size(), 1u);
    EXPECT_TRUE(has(f[0].message, "Layers of the flow thinner than h_threshold (0.01 m) reached the end"))
        << f[0].message;
    EXPECT_TRUE(has(f[0].message, "10 m3 (1.0 % of the release)")) << f[0].message;
}

TEST(RunCaveats, NotStoppedSaysHowFarFromTheStopRuleTheRunEnded) {
    RunStatistics st = stopped_run();
    st.end_reason = EndReason::end_time;
    st.simulated_time = 60.0;
    st.final_kinetic_energy = 0.77e6;
    const NumericsParams n;
    const auto c = run_caveats({st, EdgeContact{}, Frame::dem, n});
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].code, "not_stopped");
    EXPECT_TRUE(has(c[0].message, "t_end = 60 s: its kinetic energy was 0.77 of its maximum")) << c[0].message;
    EXPECT_TRUE(has(c[0].message, "still moving")) << c[0].message;

    // Near rest: says so, and asks for a check rather than a longer run.
    st.final_kinetic_energy = 1.1e3;
    const auto near = run_caveats({st, EdgeContact{}, Frame::dem, n});
    ASSERT_EQ(near.size(), 1u);
    EXPECT_TRUE(has(near[0].message, "0.0011 of its maximum, the main flow over, but the stop rule needs below 0.0001 for 1 s")) << near[0].message;

    // Both caveats: the edge first.
    EdgeContact e;
    e.low_j = 4;
    const auto both = run_caveats({st, e, Frame::dem, n});
    ASSERT_EQ(both.size(), 2u);
    EXPECT_EQ(both[0].code, "reached_edge");
    EXPECT_EQ(both[1].code, "not_stopped");
    EXPECT_TRUE(has(both[0].message, "the south side (4 cells)")) << both[0].message;

    // An interrupted run is marked incomplete instead.
    st.end_reason = EndReason::interrupted;
    EXPECT_TRUE(run_caveats({st, e, Frame::dem, n}).empty());
}

}  // namespace
}  // namespace avalanche
