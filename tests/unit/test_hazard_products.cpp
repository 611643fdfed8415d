// Hazard products computed by the observers of the time loop (MODEL.md 5):
// classification thresholds, consistency of the maxima with each other, arrival
// times, and the runout metrics against the chute geometry computed independently.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "avalanche/core/simulation.hpp"
#include "avalanche/output/hazard_maps.hpp"
#include "avalanche/output/monitoring.hpp"
#include "avalanche/output/runout.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/release.hpp"
#include "support/resident_memory.hpp"

using namespace avalanche;

TEST(HazardClass, PressureThresholds) {
    OutputParams p;  // 0.01 m, 3 and 30 kPa
    EXPECT_EQ(classify(0.005, 100.0, p), HazardClass::none) << "below the depth threshold";
    EXPECT_EQ(classify(0.02, 0.0, p), HazardClass::low);
    EXPECT_EQ(classify(0.02, 2.99, p), HazardClass::low);
    EXPECT_EQ(classify(0.02, 3.0, p), HazardClass::medium);
    EXPECT_EQ(classify(0.02, 29.9, p), HazardClass::medium);
    EXPECT_EQ(classify(0.02, 30.0, p), HazardClass::high);
}

namespace {
// Each step's impact pressure and each cell's first arrival, kept cell by cell as the
// maps once stored them (a pressure map updated with rho |u|^2 at every step, arrival
// -1 until the cell is reached), to check the maps that derive both.
struct StepRecord : StepObserver {
    StepRecord(const Grid& g, double rho) : density(rho), pressure(g.cells(), 0.0), arrival(g.cells(), -1.0) {}
    void on_start(const SimulationView& v) override { record(v); }
    void on_step(const SimulationView& v) override { record(v); }
    void record(const SimulationView& v) {
        const OutputParams out;
        for (int j = 0; j < v.grid.ny; ++j)
            for (int i = 0; i < v.grid.nx; ++i) {
                const double hn = v.state.h(i, j) * v.terrain.normal_thickness(i, j);
                if (!(hn >= out.h_threshold)) continue;
                const std::size_t k = static_cast<std::size_t>(j) * v.grid.nx + i;
                const double speed = true_speed(v.state, v.terrain, i, j);
                pressure[k] = std::max(pressure[k], density / 1000.0 * speed * speed);
                if (arrival[k] < 0.0) arrival[k] = v.t;
            }
    }
    double density;
    std::vector<double> pressure, arrival;
};

struct ChuteRun {
    ChuteGeometry chute;
    Grid grid;
    TerrainFields terrain;
    State initial;
    RunStatistics stats;
    std::unique_ptr<HazardMaps> maps;
    std::unique_ptr<MonitoringPoints> probes;
    std::unique_ptr<StepRecord> record;
};

ChuteRun run_small_chute() {
    ChuteRun r;
    r.chute.slope_deg = 35.0;
    r.chute.length = 40.0;
    r.chute.width = 10.0;
    r.chute.transition_start = 15.0;
    r.chute.transition_end = 20.0;
    r.grid = chute_grid(r.chute, 0.5);
    r.terrain = chute_terrain(r.chute, r.grid, 9.81);
    r.initial = state_at_rest(r.grid, rasterize_release(ParaboloidRelease{{5.0, 5.0}, 2.0, 1.0}, r.grid), r.terrain);
    MaterialParams m;
    m.phi_deg = 30.0;
    m.delta_deg = 22.0;
    NumericsParams n;
    n.t_end = 20.0;
    OutputParams out;
    r.maps = std::make_unique<HazardMaps>(r.grid, out, 2000.0);
    r.probes = std::make_unique<MonitoringPoints>(
        std::vector<ProbeLocation>{{"on the plane", 10.25, 5.25, 20, 10}}, 0.1, 2000.0,
        out.h_threshold);
    Simulation sim(r.grid, r.terrain, m, n, r.initial, effective_h_min(n, r.initial, r.terrain));
    sim.add_observer(r.maps.get());
    sim.add_observer(r.probes.get());
    r.record = std::make_unique<StepRecord>(r.grid, 2000.0);
    sim.add_observer(r.record.get());
    r.stats = sim.run();
    return r;
}
}  // namespace

TEST(HazardMaps, MaximaArrivalAndRunoutAreConsistent) {
    const ChuteRun r = run_small_chute();
    ASSERT_NE(r.stats.end_reason, EndReason::end_time) << "the run should stop on the runout";
    const auto& depth = r.maps->max_depth();
    const auto& speed = r.maps->max_speed();
    const auto& pressure = r.maps->max_pressure();
    const auto& arrival = r.maps->arrival_time();
    const auto& deposit = r.maps->deposit_depth();
    const OutputParams out;
    int reached = 0;
    for (std::size_t k = 0; k < depth.size(); ++k) {
        EXPECT_GE(depth[k] + 1e-15, deposit[k]) << "a deposit never exceeds the maximum depth";
        EXPECT_NEAR(pressure[k], 2.0 * speed[k] * speed[k], 1e-9 * (1.0 + pressure[k]));  // rho = 2000 kg/m3, kPa
        // To the bit the maximum of the steps' pressures and the first step reaching
        // the cell, though the maps keep neither.
        ASSERT_EQ(pressure[k], r.record->pressure[k]) << "cell " << k;
        ASSERT_EQ(arrival[k], r.record->arrival[k]) << "cell " << k;
        ASSERT_EQ(r.maps->max_pressure(k), pressure[k]);
        ASSERT_EQ(r.maps->arrival_time(k), arrival[k]);
        const bool is_reached = depth[k] >= out.h_threshold;
        EXPECT_EQ(is_reached, arrival[k] != HazardMaps::kNotReached);
        reached += is_reached;
    }
    ASSERT_GT(reached, 50);
    // Downstream of the release, the centre line is reached later the farther it is.
    const int jc = r.grid.ny / 2;
    double previous = 0.0;
    for (int i = 20; i < r.grid.nx; ++i) {
        const double a = arrival[static_cast<std::size_t>(jc) * r.grid.nx + i];
        if (a == HazardMaps::kNotReached) break;
        EXPECT_GE(a, previous) << "arrival time along the centre line at i = " << i;
        previous = a;
    }

    // Runout metrics against the chute geometry: the tip is the farthest reached
    // cell, the top the highest release cell; H and L from the chute's own integrals.
    const auto position = [&](int i, int j) {
        return std::array<double, 2>{r.chute.horizontal_distance(r.grid.x_center(i)), r.grid.y_center(j)};
    };
    const RunoutMetrics m = compute_runout(r.grid, r.terrain, r.initial, *r.maps, out, position,
                                           r.grid.cell_area());
    double x_top = 1e300, x_tip = -1e300;
    for (int j = 0; j < r.grid.ny; ++j)
        for (int i = 0; i < r.grid.nx; ++i) {
            if (r.initial.h(i, j) >= out.h_threshold) x_top = std::min(x_top, r.grid.x_center(i));
            if (depth[static_cast<std::size_t>(j) * r.grid.nx + i] >= out.h_threshold)
                x_tip = std::max(x_tip, r.grid.x_center(i));
        }
    const double fall = r.chute.elevation(x_top) - r.chute.elevation(x_tip);
    const double along = r.chute.horizontal_distance(x_tip) - r.chute.horizontal_distance(x_top);
    EXPECT_NEAR(m.fall_height_m, fall, 1e-9);
    // The farthest cell may be off the centre line: L is at least the along-slope part.
    EXPECT_GE(m.runout_length_m + 1e-9, along);
    EXPECT_LE(m.runout_length_m, std::hypot(along, r.chute.width));
    EXPECT_NEAR(m.travel_angle_deg, std::atan2(m.fall_height_m, m.runout_length_m) * 180.0 / std::numbers::pi, 1e-12);
    EXPECT_NEAR(m.runout_efficiency, m.runout_length_m / m.fall_height_m, 1e-12);
    EXPECT_DOUBLE_EQ(m.affected_area_m2, reached * r.grid.cell_area());
    // Everything stopped in the domain: the deposit holds the released volume less
    // the thin film below h_thr.
    EXPECT_LE(m.deposit_volume_m3, r.stats.released_volume * (1 + 1e-12));
    EXPECT_GT(m.deposit_volume_m3, 0.95 * r.stats.released_volume);
    // A travel angle above the friction angle would mean the mass stopped too early;
    // far below it, that it ran too far for a Coulomb material: 22 deg +- 8.
    EXPECT_GT(m.travel_angle_deg, 14.0);
    EXPECT_LT(m.travel_angle_deg, 30.0);
}

// The readers of whole maps (compute_runout, the products, the whole-map getters) look
// only inside the maps' reach box: it must hold every cell where a map holds a value, also
// after a checkpoint, or a reached cell would be lost without a sign. And the runout
// metrics read inside it must be those of reading the whole grid, to the bit (the same
// cells in the same order).
TEST(HazardMaps, TheReachBoxHoldsEveryValueAlsoAfterACheckpoint) {
    const ChuteRun r = run_small_chute();
    const OutputParams out;
    HazardMaps restored(r.grid, out, 2000.0);
    CheckpointData saved;
    r.maps->save(saved);
    restored.restore(saved);
    const ActiveBox b = r.maps->reach_box(), rb = restored.reach_box();
    ASSERT_FALSE(b.empty());
    EXPECT_LT(b.cells(), r.grid.cells() * 9 / 10) << "a box of (nearly) the whole grid would test little";
    const auto inside = [](const ActiveBox& box, int i, int j) {
        return i >= box.i0 && i < box.i1 && j >= box.j0 && j < box.j1;
    };
    const auto depth = r.maps->max_depth(), speed = r.maps->max_speed(), deposit = r.maps->deposit_depth();
    double volume = 0.0, deepest = 0.0, fastest = 0.0;
    long reached = 0, valued = 0;
    for (int j = 0; j < r.grid.ny; ++j)
        for (int i = 0; i < r.grid.nx; ++i) {
            const std::size_t k = static_cast<std::size_t>(j) * r.grid.nx + i;
            const bool value = depth[k] != 0.0 || speed[k] != 0.0 || deposit[k] != 0.0;
            valued += value;
            if (value) {
                ASSERT_TRUE(inside(b, i, j)) << "cell " << i << ", " << j << " outside the reach box";
            }
            if (depth[k] != 0.0 || speed[k] != 0.0) {
                ASSERT_TRUE(inside(rb, i, j)) << "cell " << i << ", " << j << " outside the restored box";
            }
            ASSERT_EQ(restored.max_depth()[k], depth[k]);
            // The whole grid, as compute_runout read it before it read the box only.
            deepest = std::max(deepest, depth[k]);
            fastest = std::max(fastest, speed[k]);
            if (deposit[k] != 0.0) volume += deposit[k] / r.terrain.normal_thickness(i, j) * r.grid.cell_area();
            reached += depth[k] >= out.h_threshold;
        }
    ASSERT_GT(valued, 50);
    const auto position = [&](int i, int j) {
        return std::array<double, 2>{r.chute.horizontal_distance(r.grid.x_center(i)), r.grid.y_center(j)};
    };
    const RunoutMetrics m = compute_runout(r.grid, r.terrain, r.initial, *r.maps, out, position,
                                           r.grid.cell_area());
    EXPECT_EQ(m.deposit_volume_m3, volume);
    EXPECT_EQ(m.max_depth_m, deepest);
    EXPECT_EQ(m.max_velocity_ms, fastest);
    EXPECT_EQ(m.affected_area_m2, static_cast<double>(reached) * r.grid.cell_area());
    // The restored maps (no deposit: it is not checkpointed) give the same reach.
    const RunoutMetrics mr = compute_runout(r.grid, r.terrain, r.initial, restored, out, position,
                                            r.grid.cell_area());
    EXPECT_EQ(mr.runout_length_m, m.runout_length_m);
    EXPECT_EQ(mr.affected_area_m2, m.affected_area_m2);
    EXPECT_EQ(mr.max_velocity_ms, m.max_velocity_ms);
}

// A flow that leaves the cells it reached: a patch at rest in one corner at the start, in
// the opposite corner (only) afterwards and at the end. The reach box must hold both
// patches, and the whole-map products must show both: the box of the last step alone would
// lose the first.
TEST(HazardMaps, TheReachBoxHoldsCellsTheFlowHasLeft) {
    const Grid g{60, 40, 1.0, 1.0};
    TerrainFields terrain;
    terrain.allocate(g, false, false);
    const OutputParams out;
    HazardMaps maps(g, out, 2000.0);
    State s(g);
    const auto patch = [&](int i0, int j0, double h, double hu) {
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) {
                const bool in = i >= i0 && i < i0 + 3 && j >= j0 && j < j0 + 2;
                s.h(i, j) = in ? h : 0.0;
                s.hu(i, j) = in ? hu : 0.0;
            }
    };
    const ActiveBox first{1, 4, 2, 4}, second{50, 53, 30, 32};
    patch(1, 2, 0.5, 1.0);
    maps.on_start(SimulationView{g, terrain, s, 0.0, 0, first});
    patch(50, 30, 0.4, 0.8);
    maps.on_step(SimulationView{g, terrain, s, 1.0, 1, second});
    maps.on_end(SimulationView{g, terrain, s, 1.0, 1, second});
    const ActiveBox b = maps.reach_box();
    EXPECT_TRUE(b.i0 <= 1 && b.i1 >= 53 && b.j0 <= 2 && b.j1 >= 32)
        << "reach box " << b.i0 << ".." << b.i1 << " x " << b.j0 << ".." << b.j1;
    const std::vector<double> arrival = maps.arrival_time(), pressure = maps.max_pressure();
    const std::vector<std::uint8_t> classes = maps.hazard_classes();
    const std::size_t a = 2 * 60 + 1, c = 30 * 60 + 50;  // a cell of each patch
    EXPECT_EQ(arrival[a], 0.0);
    EXPECT_EQ(arrival[c], 1.0);
    EXPECT_DOUBLE_EQ(pressure[a], 2.0 * 2.0 * 2.0);  // rho |u|^2 in kPa, u = hu / h = 2 m/s
    EXPECT_DOUBLE_EQ(pressure[c], 2.0 * 2.0 * 2.0);
    EXPECT_NE(classes[a], 0);
    EXPECT_NE(classes[c], 0);
    EXPECT_EQ(arrival[10 * 60 + 30], HazardMaps::kNotReached);  // between the patches
    EXPECT_EQ(classes[10 * 60 + 30], 0);
    const RunoutMetrics m = compute_runout(
        g, terrain, ReleaseTop{1, 2}, maps, out,
        [&](int i, int j) { return std::array<double, 2>{g.x_center(i), g.y_center(j)}; }, 1.0);
    EXPECT_EQ(m.affected_area_m2, 12.0);  // both patches, 6 cells each
    EXPECT_DOUBLE_EQ(m.max_depth_m, 0.5);
    EXPECT_DOUBLE_EQ(m.deposit_volume_m3, 6 * 0.4);  // the second patch, at the end
}

// The maps' rule, cell by cell and written out here on its own: nothing where h n <= 0;
// below h_thr only the maximum depth; at or above it the first arrival, the maximum depth
// and the maximum true speed (with the vertical component in the DEM frame). Random dry
// cells, films, cells at h_thr and flowing cells over several steps, in rows of odd
// width with a box that is not aligned: the maps must be those of the rule to the bit.
TEST(HazardMaps, EveryCellFollowsTheRuleOfTheMapsToTheBit) {
    const Grid g{37, 6, 2.0, 2.0};
    const OutputParams out;
    for (const bool metric : {false, true}) {
        TerrainFields terrain;
        terrain.allocate(g, false, metric);
        terrain.has_metric = metric;
        State s(g);
        std::uint64_t seed = 12345;
        const auto uniform = [&seed] {  // in [0, 1), a fixed sequence (LCG)
            seed = seed * 6364136223846793005ull + 1442695040888963407ull;
            return static_cast<double>(seed >> 11) * 0x1.0p-53;
        };
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) {
                terrain.normal_thickness(i, j) = 0.7 + 0.3 * uniform();
                if (metric) {
                    terrain.sx(i, j) = 2.0 * uniform() - 1.0;
                    terrain.sy(i, j) = 2.0 * uniform() - 1.0;
                }
            }
        std::vector<double> depth(g.cells(), 0.0), speed(g.cells(), 0.0), arrival(g.cells(), 0.0);
        long films = 0;  // film cells taken in, over the steps
        HazardMaps maps(g, out, 2000.0);
        const ActiveBox box{3, 34, 0, g.ny};
        for (int step = 0; step < 6; ++step) {
            const double t = 0.5 * step;
            for (int j = 0; j < g.ny; ++j)
                for (int i = box.i0; i < box.i1; ++i) {
                    // Dry, a film below h_thr, at h_thr exactly, or flowing.
                    const double pick = uniform();
                    double h = 2.0 * uniform();
                    if (pick < 0.25)
                        h = 0.0;
                    else if (pick < 0.5)
                        h = 0.009 * uniform();
                    else if (pick < 0.55)
                        h = out.h_threshold / terrain.normal_thickness(i, j);
                    s.h(i, j) = h;
                    s.hu(i, j) = h * (20.0 * uniform() - 10.0);
                    s.hv(i, j) = h * (20.0 * uniform() - 10.0);
                    const std::size_t k = static_cast<std::size_t>(j) * g.nx + i;
                    const double hn = h * terrain.normal_thickness(i, j);
                    if (hn <= 0.0) continue;
                    films += hn < out.h_threshold;
                    if (hn >= out.h_threshold) {
                        if (!(depth[k] >= out.h_threshold)) arrival[k] = t;
                        const double u = s.hu(i, j) / h, v = s.hv(i, j) / h;
                        double speed2 = u * u + v * v;
                        if (metric) {
                            const double w = terrain.sx(i, j) * u + terrain.sy(i, j) * v;
                            speed2 += w * w;
                        }
                        speed[k] = std::max(speed[k], std::sqrt(speed2));
                    }
                    depth[k] = std::max(depth[k], hn);
                }
            const SimulationView view{g, terrain, s, t, static_cast<std::uint64_t>(step), box};
            if (step == 0)
                maps.on_start(view);
            else
                maps.on_step(view);
        }
        long flowing = 0;
        for (std::size_t k = 0; k < g.cells(); ++k) {
            ASSERT_EQ(maps.max_depth()[k], depth[k])
                << "cell " << k << (metric ? ", DEM frame" : "");
            ASSERT_EQ(maps.max_speed()[k], speed[k])
                << "cell " << k << (metric ? ", DEM frame" : "");
            const double a = depth[k] >= out.h_threshold ? arrival[k] : HazardMaps::kNotReached;
            ASSERT_EQ(maps.arrival_time(k), a) << "cell " << k << (metric ? ", DEM frame" : "");
            flowing += depth[k] >= out.h_threshold;
        }
        EXPECT_GT(flowing, 50);  // both kinds of cell are there to test
        EXPECT_GT(films, 100);
    }
}

// On a large DEM the maps hold memory only where the flow went: made, read whole and
// classified, the maps of a 2000 x 2000 grid (32 MB each) stay unwritten.
TEST(HazardMaps, MapsOfALargeGridHoldNoMemoryUntilTheFlowReachesThem) {
    if (test::resident_bytes() < 0) GTEST_SKIP() << "no /proc/self/statm";
    if (!test::untouched_reads_stay_unmade())
        GTEST_SKIP() << "this kernel makes a page on every read fault (no shared zero page): "
                        "reading the maps whole makes them resident, written or not";
    const long long before = test::resident_bytes();
    const Grid g{2000, 2000, 1.0, 1.0};
    const HazardMaps maps(g, OutputParams{}, 2000.0);
    double sum = 0.0;
    for (const double d : maps.max_depth()) sum += d;
    for (const double s : maps.max_speed()) sum += s;
    for (const double d : maps.deposit_depth()) sum += d;
    EXPECT_EQ(sum, 0.0);
    EXPECT_EQ(maps.arrival_time(123456), HazardMaps::kNotReached);
    EXPECT_EQ(maps.max_pressure(123456), 0.0);
    const long long grown = test::resident_bytes() - before;
    EXPECT_LT(grown, 16ll << 20) << "the maps of unreached cells were written";
}

TEST(MonitoringPoints, SeriesSampledAtTheIntervalAndConsistent) {
    const ChuteRun r = run_small_chute();
    const auto& s = r.probes->series().at(0);
    ASSERT_GT(s.size(), 20u);
    EXPECT_EQ(s.front().t, 0.0);
    const double thr = OutputParams{}.h_threshold;
    double max_h = 0.0;
    int flowing = 0, films = 0;
    for (std::size_t k = 1; k < s.size(); ++k) {
        EXPECT_GT(s[k].t, s[k - 1].t);
        EXPECT_NEAR(s[k].pressure, 2.0 * s[k].speed * s[k].speed, 1e-9 * (1 + s[k].pressure));
        max_h = std::max(max_h, s[k].h);
        if (s[k].h >= thr) {
            // The chute frame's speed: the velocity's magnitude (no vertical part).
            EXPECT_NEAR(s[k].speed, std::hypot(s[k].u, s[k].v), 1e-12 * (1 + s[k].speed));
            flowing += s[k].speed > 0.0;
        } else if (s[k].h > 0.0) {
            // A film below h_thr, as in the maps: no flowing material, no pressure.
            EXPECT_EQ(s[k].u, 0.0);
            EXPECT_EQ(s[k].v, 0.0);
            EXPECT_EQ(s[k].speed, 0.0);
            EXPECT_EQ(s[k].pressure, 0.0);
            ++films;
        }
    }
    // The probe sits on the path: the flow passed it, and left a film behind.
    EXPECT_GT(max_h, 0.01);
    EXPECT_GT(flowing, 5);
    EXPECT_GT(films, 0);
    const std::size_t k = static_cast<std::size_t>(r.probes->points()[0].j) * r.grid.nx + r.probes->points()[0].i;
    EXPECT_LE(max_h, r.maps->max_depth()[k] + 1e-12) << "samples never exceed the per-step maximum";
}
