// Checkpoints in process: every value written by write_checkpoint reads back bit for
// bit, and observers restored from a checkpoint taken mid-run end with exactly the
// maps, monitoring series, snapshots and statistics of the run that never stopped.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "avalanche/core/error.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/io/checkpoint_file.hpp"
#include "avalanche/io/effective_config.hpp"
#include "avalanche/io/results_writer.hpp"
#include "avalanche/output/hazard_maps.hpp"
#include "avalanche/output/monitoring.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/release.hpp"
#include "io_test_support.hpp"
#include "support/same_bits.hpp"

namespace avalanche {
namespace {

using test::same_bits;

// A 10 m x 4 m chute of 0.25 m cells with a box release; two monitoring points.
struct Scene {
    Scenario scenario;
    Grid grid;
    TerrainFields terrain;
    State initial;
    double h_min = 0.0;
    ResultsMetadata meta;
    std::vector<ProbeLocation> probes;

    Scene() {
        ChuteGeometry chute;
        chute.slope_deg = 35.0;
        chute.length = 10.0;
        chute.width = 4.0;
        scenario.terrain = chute;
        scenario.release = ReleaseShape{BoxRelease{{1.0, 3.0}, {1.5, 2.5}, 0.5}};
        scenario.cell_size = 0.25;
        scenario.numerics.t_end = 1.0;
        scenario.numerics.output_interval = 0.25;
        grid = chute_grid(chute, scenario.cell_size);
        terrain = chute_terrain(chute, grid, scenario.numerics.gravity);
        initial = state_at_rest(
            grid, rasterize_release(std::get<ReleaseShape>(scenario.release), grid), terrain);
        h_min = effective_h_min(scenario.numerics, initial, terrain);
        meta.geotransform = {0.0, 0.25, 0.0, 4.0, 0.0, -0.25};
        meta.config = effective_config(scenario);
        meta.config_hash = config_hash(meta.config);
        meta.h_min = h_min;
        probes = {{"upper", 2.1, 2.1, 8, 8}, {"lower", 6.1, 2.1, 24, 8}};
    }
};

struct Observers {
    ResultsWriter results;
    HazardMaps maps;
    MonitoringPoints probes;
    Observers(const Scene& s, const std::string& path)
        : results(path, s.grid, s.meta),
          maps(s.grid, s.scenario.output, s.scenario.material.density),
          probes(s.probes, 0.025, s.scenario.material.density, s.scenario.output.h_threshold) {}
    void attach(Simulation& sim) {
        sim.add_observer(&results);
        sim.add_observer(&maps);
        sim.add_observer(&probes);
    }
};

CheckpointInfo info_of(const Scene& s, double interval) {
    return {s.meta.config, s.meta.config_hash, "/", "fingerprint", interval, 1, "test", "test"};
}

TEST(CheckpointRoundTrip, ResumedObserversEndExactlyAsTheUninterruptedRun) {
    test::ScratchDir dir("ckpt-roundtrip");
    const Scene s;
    const std::string ckpt = dir.file("checkpoint.h5");

    // The reference run keeps its first checkpoint (t = 0.3 s, mid-run, between outputs).
    RunStatistics ref_stats;
    Observers ref(s, dir.file("ref.h5"));
    {
        Simulation sim(s.grid, s.terrain, s.scenario.material, s.scenario.numerics, s.initial,
                       s.h_min);
        ref.attach(sim);
        sim.set_checkpointing(0.3, [&](const SimulationCheckpoint& c) {
            if (!std::filesystem::exists(ckpt))
                write_checkpoint(ckpt, info_of(s, 0.3), c, s.grid, &ref.results);
        });
        ref_stats = sim.run();
        ref.results.finish(ref_stats);
    }
    ASSERT_TRUE(std::filesystem::exists(ckpt));

    const CheckpointContents c = read_checkpoint(ckpt);
    EXPECT_GE(c.loop.t, 0.3 - 1e-12);
    EXPECT_LT(c.loop.t, 0.5);
    EXPECT_EQ(c.nx, s.grid.nx);
    EXPECT_EQ(c.ny, s.grid.ny);
    EXPECT_EQ(c.info.checkpoint_interval, 0.3);
    EXPECT_EQ(c.info.config_hash, s.meta.config_hash);

    Observers resumed(s, dir.file("resumed.h5"));
    Simulation sim(s.grid, s.terrain, s.scenario.material, s.scenario.numerics, s.initial, s.h_min);
    resumed.attach(sim);
    sim.set_checkpointing(0.3, [](const SimulationCheckpoint&) {});
    resumed.results.resume_from(ckpt);
    EXPECT_EQ(resumed.results.snapshots(), 2u)
        << "t = 0 and 0.25 s were written before the checkpoint";
    sim.resume(c.loop, c.h, c.hu, c.hv, c.observers);
    // The stepper's energy cap is fixed by the first step of the run; recomputing it
    // from the resumed state would give another cap (a different run where it binds).
    EXPECT_TRUE(std::isfinite(c.loop.energy_budget));
    EXPECT_EQ(sim.stepper().energy_budget(), c.loop.energy_budget);
    const RunStatistics stats = sim.run();
    resumed.results.finish(stats);

    EXPECT_EQ(stats.steps, ref_stats.steps);
    EXPECT_EQ(stats.simulated_time, ref_stats.simulated_time);
    EXPECT_EQ(stats.cell_updates, ref_stats.cell_updates);
    EXPECT_EQ(stats.released_volume, ref_stats.released_volume);
    EXPECT_EQ(stats.final_volume, ref_stats.final_volume);
    EXPECT_EQ(stats.outflow_volume, ref_stats.outflow_volume);
    EXPECT_EQ(stats.max_kinetic_energy, ref_stats.max_kinetic_energy);
    EXPECT_EQ(stats.end_reason, ref_stats.end_reason);
    EXPECT_TRUE(same_bits(resumed.maps.max_depth(), ref.maps.max_depth()));
    EXPECT_TRUE(same_bits(resumed.maps.max_speed(), ref.maps.max_speed()));
    EXPECT_TRUE(same_bits(resumed.maps.max_pressure(), ref.maps.max_pressure()));
    EXPECT_TRUE(same_bits(resumed.maps.arrival_time(), ref.maps.arrival_time()));
    EXPECT_TRUE(same_bits(resumed.maps.deposit_depth(), ref.maps.deposit_depth()));
    ASSERT_EQ(resumed.probes.series().size(), 2u);
    for (std::size_t p = 0; p < 2; ++p) {
        const auto& a = ref.probes.series()[p];
        const auto& b = resumed.probes.series()[p];
        ASSERT_EQ(a.size(), b.size());
        EXPECT_GT(a.size(), 20u);
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(ProbeSample)), 0)
            << "point " << p;
    }
    for (const char* set : {"time", "h", "u", "v"}) {
        const auto a = test::read_h5_dataset(dir.file("ref.h5"), set);
        const auto b = test::read_h5_dataset(dir.file("resumed.h5"), set);
        EXPECT_EQ(a.dims, b.dims) << set;
        EXPECT_TRUE(same_bits(a.values, b.values)) << set;
    }
    EXPECT_EQ(test::read_h5_dataset(dir.file("resumed.h5"), "time").values.size(), 5u)
        << "0, 0.25, ... 1 s, once each";
}

TEST(CheckpointRoundTrip, EveryValueReadsBackBitForBit) {
    test::ScratchDir dir("ckpt-values");
    const Scene s;
    State state = s.initial;
    state.hu(3, 4) = -0.0;  // sign of zero kept
    state.hv(5, 6) = 1e-300;
    LoopState loop;
    loop.t = 0.1 + 0.2;  // not a short decimal
    loop.steps = 123456789012345ULL;
    loop.outputs_done = 7;
    loop.next_output = 1.75;
    loop.last_output_t = 1.5;
    loop.ke_max = 3.0 / 7.0;
    loop.quiet_since = -1.0;
    loop.released_volume = 1.0 / 3.0;
    loop.outflow_volume = 2e-17;
    loop.cell_updates = (1ULL << 62) + 1;
    loop.next_checkpoint = 2.0;
    loop.energy_budget = std::numeric_limits<double>::infinity();
    SimulationCheckpoint c{loop, state, {}};
    c.observers.reals["a/b"] = {std::nan(""), -std::numeric_limits<double>::infinity(), 5e-324};
    c.observers.reals["empty"] = {};
    c.observers.integers["a/counts"] = {-5, 0, std::numeric_limits<std::int64_t>::max()};
    const std::string path = dir.file("c.h5");
    write_checkpoint(path, info_of(s, 0.5), c, s.grid, nullptr);
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

    const CheckpointContents r = read_checkpoint(path);
    EXPECT_EQ(r.loop.t, loop.t);
    EXPECT_EQ(r.loop.steps, loop.steps);
    EXPECT_EQ(r.loop.outputs_done, loop.outputs_done);
    EXPECT_EQ(r.loop.next_output, loop.next_output);
    EXPECT_EQ(r.loop.last_output_t, loop.last_output_t);
    EXPECT_EQ(r.loop.ke_max, loop.ke_max);
    EXPECT_EQ(r.loop.quiet_since, loop.quiet_since);
    EXPECT_EQ(r.loop.released_volume, loop.released_volume);
    EXPECT_EQ(r.loop.outflow_volume, loop.outflow_volume);
    EXPECT_EQ(r.loop.cell_updates, loop.cell_updates);
    EXPECT_EQ(r.loop.next_checkpoint, loop.next_checkpoint);
    EXPECT_EQ(r.loop.energy_budget, loop.energy_budget);
    EXPECT_TRUE(same_bits(r.h, state.h.packed()));
    EXPECT_TRUE(same_bits(r.hu, state.hu.packed()));
    EXPECT_TRUE(same_bits(r.hv, state.hv.packed()));
    EXPECT_TRUE(same_bits(r.observers.reals.at("a/b"), c.observers.reals.at("a/b")));
    EXPECT_TRUE(r.observers.reals.at("empty").empty());
    EXPECT_EQ(r.observers.integers.at("a/counts"), c.observers.integers.at("a/counts"));
    EXPECT_EQ(r.info.config, s.meta.config);
    EXPECT_EQ(r.info.working_dir, "/");
}

TEST(CheckpointRoundTrip, ObserversRefuseDataThatDoesNotFitTheRun) {
    const Scene s;
    HazardMaps maps(s.grid, s.scenario.output, 200.0);
    CheckpointData data;
    data.reals["hazard_maps/max_depth"] = std::vector<double>(s.grid.cells(), 1.0);
    EXPECT_THROW(maps.restore(data), InputError) << "max_speed missing";
    data.reals["hazard_maps/max_speed"] = std::vector<double>(3, 1.0);  // wrong size
    data.reals["hazard_maps/max_pressure"] = std::vector<double>(s.grid.cells(), 1.0);
    data.reals["hazard_maps/arrival_time"] = std::vector<double>(s.grid.cells(), 1.0);
    EXPECT_THROW(maps.restore(data), InputError);
    EXPECT_EQ(maps.max_depth()[0], 0.0) << "a refused checkpoint leaves the maps untouched";

    MonitoringPoints probes(s.probes, 0.1, 200.0, OutputParams{}.h_threshold);
    CheckpointData m;
    m.integers["monitoring/sample_counts"] = {1, 1};
    m.reals["monitoring/samples"] = std::vector<double>(6, 0.0);  // one sample for two counts
    m.reals["monitoring/next_sample_time"] = {0.1};
    EXPECT_THROW(probes.restore(m), InputError);
}

TEST(CheckpointRoundTrip, ReadingRefusesFilesThatAreNotCheckpoints) {
    test::ScratchDir dir("ckpt-refuse");
    EXPECT_THROW(read_checkpoint(dir.file("missing.h5")), InputError);
    const std::string results = dir.file("results.h5");
    {
        const Scene s;
        ResultsWriter w(results, s.grid, s.meta);
        RunStatistics st;
        w.finish(st);
    }
    try {
        read_checkpoint(results);
        FAIL() << "results.h5 is not a checkpoint";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(results + ": not a complete checkpoint"),
                  std::string::npos)
            << e.what();
    }
}

TEST(CheckpointRoundTrip, ResumeRefusesARegimeThatIsNotFlags) {
    // The cells' Savage-Hutter regimes (Stepper::regime) travel with the checkpoint; a
    // resumed run takes them, and refuses a dataset that is missing, has another length
    // or holds a value that is not a regime (0 to 3).
    const Scene s;
    LoopState loop;
    State state = s.initial;
    CheckpointData saved;
    bool taken = false;
    {
        Simulation sim(s.grid, s.terrain, s.scenario.material, s.scenario.numerics, s.initial,
                       s.h_min);
        sim.set_checkpointing(0.3, [&](const SimulationCheckpoint& c) {
            if (taken) return;
            loop = c.loop;
            state = c.state;
            saved = c.observers;
            taken = true;
        });
        sim.run();
    }
    ASSERT_TRUE(taken);
    const auto& regime = saved.integers.at("solver/regime");
    ASSERT_EQ(regime.size(), state.h.packed_size());
    long passive = 0;
    for (const std::int64_t r : regime) passive += r != 3;
    EXPECT_GT(passive, 0) << "the checkpoint should hold some passive cells";

    const auto resume_with = [&](const CheckpointData& observers) {
        Simulation sim(s.grid, s.terrain, s.scenario.material, s.scenario.numerics, s.initial,
                       s.h_min);
        sim.resume(loop, state.h.packed(), state.hu.packed(), state.hv.packed(), observers);
        const CellVector<RegimeFlags> restored = sim.stepper().regime();
        return state.h.packed<std::int64_t>(restored.data());
    };
    EXPECT_EQ(resume_with(saved), regime);
    CheckpointData bad = saved;
    bad.integers["solver/regime"][7] = 7;
    EXPECT_THROW(resume_with(bad), InputError);
    bad.integers["solver/regime"].pop_back();
    EXPECT_THROW(resume_with(bad), InputError);
    bad.integers.erase("solver/regime");
    EXPECT_THROW(resume_with(bad), InputError);
}

}  // namespace
}  // namespace avalanche
