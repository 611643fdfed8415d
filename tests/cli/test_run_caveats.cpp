// A run's caveats end to end (output/run_caveats.hpp, docs/products.md "Caveats"): a flow
// that runs off the coarse parametric chute, and one cut short by t_end, are flagged in
// the log, summary.json, report.md and report.html, with numbers that match the products.
#include <gtest/gtest.h>

#include <cstdio>

#include "avalanche/gis/raster_reader.hpp"
#include "batch_test_support.hpp"
#include "cli_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The coarse parametric chute run with `flags` into dir/out; fails the test on a non-zero exit.
test::ProcessResult run_chute(const test::ScratchDir& dir, const std::string& flags) {
    const std::string scenario = dir.write("base.toml", test::kCoarseParametricChute);
    const auto r = test::run_binary(dir, "run -q --scenario '" + scenario + "' " + flags + " --out '" +
                                             dir.file("out") + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r;
}

TEST(RunCaveatsCli, AFlowOffTheChuteIsFlaggedWithTheCellsOfTheMapAtTheEdge) {
    test::ScratchDir dir("caveats-edge");
    const std::string out = dir.file("out");
    // delta 15: the flow crosses the flat runout zone and leaves at the chute's lower end.
    const auto r = run_chute(dir, "--delta 15");
    ASSERT_EQ(r.exit_code, 0);
    const auto s = test::read_json(out + "/summary.json");
    ASSERT_GE(s["caveats"].size(), 1u) << s.dump(2);
    EXPECT_EQ(s["caveats"][0]["code"], "reached_edge");
    const std::string message = s["caveats"][0]["message"].get<std::string>();

    // The cells it names are the reached cells of max_depth.tif's last column (i = nx - 1:
    // the lower end), counted from the map.
    const gis::RasterData depth = gis::read_geotiff(out + "/max_depth.tif");
    const int nx = depth.geo.grid.nx, ny = depth.geo.grid.ny;
    int lower_end = 0;
    for (int j = 0; j < ny; ++j) {
        const double v = depth.values[static_cast<std::size_t>(j) * nx + nx - 1];
        lower_end += depth.nodata ? v != *depth.nodata : v >= 0.01;
    }
    ASSERT_GT(lower_end, 0) << "the flow should reach the lower end";
    EXPECT_TRUE(has(message, "the lower end (" + std::to_string(lower_end) + " cells)")) << message;
    // ... and the volume that left is summary.json's outflow.
    const double outflow = s["volume"]["outflow_m3"].get<double>();
    const double released = s["volume"]["released_m3"].get<double>();
    char expected[96];
    std::snprintf(expected, sizeof expected, "%.3g m3 (%.1f %% of the release) left the grid", outflow,
                  100.0 * outflow / released);
    EXPECT_TRUE(has(message, expected)) << message << "\nexpected: " << expected;

    // The log says it (warnings pass --quiet), and both reports, before the results.
    EXPECT_TRUE(has(r.err, "warning: " + message)) << r.err;
    const std::string md = test::read_text(out + "/report.md");
    ASSERT_TRUE(has(md, "Caveats of this run")) << md.substr(0, 600);
    EXPECT_LT(md.find(message), md.find("## Results in brief"));
    const std::string html = test::read_text(out + "/report.html");
    EXPECT_TRUE(has(html, "<li data-code=\"reached_edge\">")) << html.substr(0, 2000);
}

TEST(RunCaveatsCli, ARunCutShortByTEndSaysItsKineticEnergy) {
    test::ScratchDir dir("caveats-time");
    const std::string out = dir.file("out");
    const auto r = run_chute(dir, "--t-end 2");
    ASSERT_EQ(r.exit_code, 0);
    const auto s = test::read_json(out + "/summary.json");
    ASSERT_EQ(s["end_reason"], "end_time");
    ASSERT_EQ(s["caveats"].size(), 1u) << s.dump(2);  // at 2 s the flow is still on the slope
    EXPECT_EQ(s["caveats"][0]["code"], "not_stopped");
    char expected[96];
    std::snprintf(expected, sizeof expected, "t_end = 2 s: its kinetic energy was %.2g of its maximum",
                  s["final_kinetic_energy_fraction"].get<double>());
    const std::string message = s["caveats"][0]["message"].get<std::string>();
    EXPECT_TRUE(has(message, expected)) << message;
    EXPECT_TRUE(has(message, "still moving")) << message;
    EXPECT_TRUE(has(r.err, "warning: " + message)) << r.err;
}

// The default t_end (300 s) lets a real path stop by itself: avaKot on 20 m cells stops by
// the kinetic-energy rule at about 64 s, past the former default of 60 s, and nothing of it
// reaches the end of the terrain (0.1 % of the release leaves in films, below the caveat).
TEST(RunCaveatsCli, TheBundledAvaKotPathStopsWithinTheDefaultEndTimeWithoutCaveats) {
    test::ScratchDir dir("caveats-avakot");
    const std::string out = dir.file("out");
    const auto r = test::run_binary(dir, "run -q --dem '" + test::avaKot("avaKot_dem.tif") + "' --release '" +
                                             test::avaKot("avaKot_release.gpkg") +
                                             "' --cell-size 20 --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto s = test::read_json(out + "/summary.json");
    EXPECT_EQ(s["parameters"]["numerics"]["t_end"], 300.0);
    EXPECT_EQ(s["end_reason"], "stopped_kinetic_energy");
    EXPECT_GT(s["simulated_time_s"].get<double>(), 60.0);
    EXPECT_TRUE(s["caveats"].empty()) << s["caveats"].dump(2);
    EXPECT_GT(s["volume"]["outflow_m3"].get<double>(), 0.0);
    EXPECT_EQ(r.err, "");
    EXPECT_EQ(test::read_text(out + "/report.md").find("Caveats"), std::string::npos);
}

}  // namespace
}  // namespace avalanche
