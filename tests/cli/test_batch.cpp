// `avalanche-hazard batch` end to end on the coarse parametric chute: the physics trend
// the issue asks for (runout falls as delta rises), comparison.csv against each
// summary.json, the envelope maps, and resuming after a lost scenario.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "avalanche/app/cli.hpp"
#include "avalanche/gis/raster_reader.hpp"
#include "avalanche/io/effective_config.hpp"
#include "batch_test_support.hpp"
#include "checkpoint_test_support.hpp"

namespace avalanche {
namespace {

namespace fs = std::filesystem;

int run_batch(const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"avalanche-hazard", "batch", "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args);
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    EXPECT_NE(it, header.end()) << name;
    return static_cast<std::size_t>(it - header.begin());
}

TEST(Batch, DeltaSweepOnTheChute) {
    test::ScratchDir dir("batch-delta");
    const auto base = dir.write("base.toml", test::kCoarseParametricChute);
    const std::string out = dir.file("out");
    ASSERT_EQ(run_batch({"--scenario", base, "--sweep", "delta=15,20,25,30", "--out", out,
                         "--parallel", "2"}),
              0);

    const auto csv = test::read_csv(out + "/comparison.csv");
    ASSERT_EQ(csv.size(), 5u);  // header + one row per scenario
    const std::vector<std::string> expected_header = {"id",
                                                      "delta_deg",
                                                      "runout_m",
                                                      "travel_angle_deg",
                                                      "runout_efficiency",
                                                      "affected_area_m2",
                                                      "max_depth_m",
                                                      "max_velocity_ms",
                                                      "deposit_volume_m3",
                                                      "end_reason",
                                                      "caveats",
                                                      "wall_s"};
    EXPECT_EQ(csv[0], expected_header);
    const std::vector<std::pair<std::string, std::string>> runout_keys = {
        {"runout_m", "runout_length_m"},
        {"travel_angle_deg", "travel_angle_deg"},
        {"runout_efficiency", "runout_efficiency"},
        {"affected_area_m2", "affected_area_m2"},
        {"max_depth_m", "max_depth_m"},
        {"max_velocity_ms", "max_velocity_ms"},
        {"deposit_volume_m3", "deposit_volume_m3"}};
    std::vector<double> runout;
    std::map<std::string, std::string> caveats;
    for (std::size_t r = 1; r < csv.size(); ++r) {
        const auto& row = csv[r];
        ASSERT_EQ(row.size(), expected_header.size());
        EXPECT_EQ(row[0], "delta=" + row[1]);
        if (r > 1) {
            EXPECT_LT(csv[r - 1][0], row[0]);  // sorted by id
        }
        const auto summary = test::read_json(out + "/" + row[0] + "/summary.json");
        EXPECT_EQ(std::strtod(row[1].c_str(), nullptr),
                  summary["parameters"]["material"]["delta_deg"].get<double>());
        for (const auto& [col, key] : runout_keys)
            EXPECT_EQ(std::strtod(row[column(csv[0], col)].c_str(), nullptr),
                      summary["runout"][key].get<double>())
                << row[0] << " " << col;
        EXPECT_EQ(row[column(csv[0], "end_reason")], summary["end_reason"].get<std::string>());
        std::string codes;
        for (const auto& c : summary["caveats"]) {
            if (!codes.empty()) codes += ';';
            codes += c["code"].get<std::string>();
        }
        EXPECT_EQ(row[column(csv[0], "caveats")], codes) << row[0];
        caveats[row[0]] = codes;
        EXPECT_EQ(std::strtod(row.back().c_str(), nullptr), summary["wall_s"].get<double>());
        runout.push_back(summary["runout"]["runout_length_m"].get<double>());
    }
    // The least friction runs off the chute's lower end; the most stops on it.
    EXPECT_EQ(caveats["delta=15"], "reached_edge");
    EXPECT_EQ(caveats["delta=30"], "");
    EXPECT_EQ(test::read_text(out + "/delta=30/report.md").find("Caveats"), std::string::npos);
    EXPECT_NE(test::read_text(out + "/delta=15/report.md").find("Caveats of this run"), std::string::npos);
    // Issue 4: a higher bed friction angle stops the flow earlier.
    for (std::size_t k = 1; k < runout.size(); ++k)
        EXPECT_LT(runout[k], runout[k - 1]) << "delta index " << k;

    // Envelopes: frequency in [0, 1], 1 where every scenario reached; max >= each map.
    const auto freq = gis::read_geotiff(out + "/impact_frequency.tif");
    const auto envelope = gis::read_geotiff(out + "/envelope_max_depth.tif");
    std::vector<int> reached(freq.values.size(), 0);
    for (std::size_t r = 1; r < csv.size(); ++r) {
        const auto depth = gis::read_geotiff(out + "/" + csv[r][0] + "/max_depth.tif");
        ASSERT_EQ(depth.values.size(), envelope.values.size());
        for (std::size_t k = 0; k < depth.values.size(); ++k) {
            if (depth.values[k] == *depth.nodata) continue;
            ++reached[k];
            EXPECT_GE(envelope.values[k], depth.values[k]) << k;
        }
    }
    int everywhere = 0;
    for (std::size_t k = 0; k < freq.values.size(); ++k) {
        EXPECT_GE(freq.values[k], 0.0);
        EXPECT_LE(freq.values[k], 1.0);
        EXPECT_FLOAT_EQ(freq.values[k], reached[k] / 4.0) << k;
        if (reached[k] == 4) ++everywhere;
    }
    EXPECT_GT(everywhere, 0);
    for (const char* f : {"envelope_max_velocity.tif", "envelope_max_pressure.tif",
                          "envelope_min_arrival_time.tif", "runout_vs_delta_deg.svg",
                          "max_velocity_vs_delta_deg.svg", "comparison.md", "manifest.json"})
        EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
    EXPECT_NE(test::read_text(out + "/comparison.md").find("Longest runout: **delta=15**"),
              std::string::npos);
    const auto manifest = test::read_json(out + "/manifest.json");
    ASSERT_EQ(manifest["scenarios"].size(), 4u);
    for (const auto& s : manifest["scenarios"]) EXPECT_TRUE(s["complete"].get<bool>());
}

TEST(Batch, ResumeRecomputesOnlyTheLostScenario) {
    test::ScratchDir dir("batch-resume");
    const auto base = dir.write("base.toml", test::kCoarseParametricChute);
    const std::string out = dir.file("out");
    const std::vector<std::string> args = {"--scenario",  base,    "--sweep",
                                           "delta=25,30", "--out", out};
    ASSERT_EQ(run_batch(args), 0);
    const auto before = test::read_csv(out + "/comparison.csv");
    const auto kept = fs::last_write_time(out + "/delta=25/summary.json");
    const auto kept_map = fs::last_write_time(out + "/delta=25/max_depth.tif");
    fs::remove(out + "/delta=30/summary.json");

    ASSERT_EQ(run_batch(args), 0);  // same command: resumes, no --overwrite needed
    EXPECT_EQ(fs::last_write_time(out + "/delta=25/summary.json"), kept);
    EXPECT_EQ(fs::last_write_time(out + "/delta=25/max_depth.tif"), kept_map);
    EXPECT_TRUE(fs::exists(out + "/delta=30/summary.json"));
    const auto after = test::read_csv(out + "/comparison.csv");
    ASSERT_EQ(after.size(), before.size());
    for (std::size_t r = 0; r < after.size(); ++r) {
        // Everything but the wall-clock time of the recomputed scenario is identical.
        auto a = after[r], b = before[r];
        if (r > 0 && a[0] == "delta=30") a.back() = b.back() = "";
        EXPECT_EQ(a, b) << r;
    }
    // The document must outlive the loop: a range-for over a member of a temporary
    // reads freed memory (found by AddressSanitizer).
    const auto manifest = test::read_json(out + "/manifest.json");
    for (const auto& s : manifest["scenarios"]) EXPECT_TRUE(s["complete"].get<bool>());

    // A changed base configuration invalidates every scenario (the hash differs).
    dir.write("base.toml",
              std::string(test::kCoarseParametricChute) + "\n[output]\nh_threshold = 0.02\n");
    ASSERT_EQ(run_batch(args), 0);
    EXPECT_NE(fs::last_write_time(out + "/delta=25/summary.json"), kept);
}

// The version number is the same for every commit: what tells an upgraded program from
// the one that computed a scenario is the source hash in its summary and the manifest.
TEST(Batch, ResumeRecomputesWhatAProgramBuiltFromOtherSourcesComputed) {
    test::ScratchDir dir("batch-sources");
    const auto base = dir.write("base.toml", test::kCoarseParametricChute);
    const std::string out = dir.file("out");
    const std::vector<std::string> args = {"--scenario",  base,    "--sweep",
                                           "delta=25,30", "--out", out};
    ASSERT_EQ(run_batch(args), 0);
    auto manifest = test::read_json(out + "/manifest.json");
    EXPECT_EQ(manifest["batch"]["source_hash"], source_hash());
    for (const auto& s : manifest["scenarios"]) EXPECT_EQ(s["source_hash"], source_hash());
    EXPECT_EQ(test::read_json(out + "/delta=25/summary.json")["source_hash"], source_hash());

    // delta=30 as an older build left it: its summary and its manifest entry carry
    // another source hash.
    auto summary = test::read_json(out + "/delta=30/summary.json");
    summary["source_hash"] = "0123456789abcdef";
    std::ofstream(out + "/delta=30/summary.json") << summary.dump(2);
    for (auto& s : manifest["scenarios"])
        if (s["id"] == "delta=30") s["source_hash"] = "0123456789abcdef";
    std::ofstream(out + "/manifest.json") << manifest.dump(2);
    const auto kept = fs::last_write_time(out + "/delta=25/summary.json");

    ASSERT_EQ(run_batch(args), 0);
    EXPECT_EQ(fs::last_write_time(out + "/delta=25/summary.json"), kept);
    EXPECT_EQ(test::read_json(out + "/delta=30/summary.json")["source_hash"], source_hash());
    manifest = test::read_json(out + "/manifest.json");
    for (const auto& s : manifest["scenarios"]) {
        EXPECT_EQ(s["source_hash"], source_hash());
        EXPECT_TRUE(s["complete"].get<bool>());
    }

    // A manifest written before the hash was recorded (no key): every scenario again.
    for (auto& s : manifest["scenarios"]) s.erase("source_hash");
    std::ofstream(out + "/manifest.json") << manifest.dump(2);
    ASSERT_EQ(run_batch(args), 0);
    EXPECT_NE(fs::last_write_time(out + "/delta=25/summary.json"), kept);
}

// Ctrl-C during the second of three scenarios: the comparison says which scenario was
// interrupted and which never ran (both were reported as "failed", with no reason, and
// linked a report.md the scenario never run does not have).
TEST(Batch, InterruptedAndNeverStartedScenariosAreNotReportedAsFailed) {
    test::ScratchDir dir("batch-interrupt");
    // Cells of 0.25 m, not 0.5: a scenario runs for about a second, not 0.2 s, so
    // that the signal (acted on within 0.1 s) finds the second one still running on a
    // fast machine too.
    std::string chute = test::kCoarseParametricChute;
    const std::string coarse = "cell_size = 0.5";
    ASSERT_NE(chute.find(coarse), std::string::npos);
    chute.replace(chute.find(coarse), coarse.size(), "cell_size = 0.25");
    const auto base = dir.write("base.toml", chute);
    const std::string out = dir.file("out");
    test::ChildRun batch(dir,
                         {"batch", "--quiet", "--scenario", base, "--sweep", "delta=22,24,26",
                          "--parallel", "1", "--out", out},
                         "batch");
    // The second scenario is in its time loop once its results.h5 is open.
    ASSERT_TRUE(batch.wait_for_file(out + "/delta=24/results.h5.part", std::chrono::seconds(120)))
        << batch.stderr_text();
    batch.signal(SIGINT);
    const int status = batch.wait();
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 6) << batch.stderr_text();
    EXPECT_EQ(test::read_json(out + "/delta=24/summary.json")["end_reason"], "interrupted");
    EXPECT_FALSE(fs::exists(out + "/delta=26"));

    const auto csv = test::read_csv(out + "/comparison.csv");
    ASSERT_EQ(csv.size(), 4u);
    const std::size_t end = column(csv[0], "end_reason");
    EXPECT_EQ(csv[1][0], "delta=22");
    EXPECT_EQ(csv[1][end], test::read_json(out + "/delta=22/summary.json")["end_reason"]);
    EXPECT_EQ(csv[2][0], "delta=24");
    EXPECT_EQ(csv[2][end], "interrupted");
    EXPECT_EQ(csv[2][column(csv[0], "runout_m")], "") << "partial results are not compared";
    EXPECT_EQ(csv[3][0], "delta=26");
    EXPECT_EQ(csv[3][end], "not run");
    for (const auto& row : csv) EXPECT_EQ(row.size(), csv[0].size());

    const std::string md = test::read_text(out + "/comparison.md");
    EXPECT_EQ(md.find("failed"), std::string::npos) << md;
    EXPECT_NE(md.find("| [delta=24](delta=24/report.md) | 24 | | | | | interrupted |"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| delta=26 | 26 | | | | | not run |"), std::string::npos) << md;
    EXPECT_TRUE(fs::exists(out + "/delta=24/report.md"));
    EXPECT_NE(test::read_text(out + "/report.html").find("data-value=\"not run\""),
              std::string::npos);

    const auto manifest = test::read_json(out + "/manifest.json");
    std::map<std::string, nlohmann::json> entries;
    for (const auto& e : manifest["scenarios"]) entries[e["id"].get<std::string>()] = e;
    EXPECT_TRUE(entries["delta=22"]["complete"].get<bool>());
    EXPECT_FALSE(entries["delta=24"]["complete"].get<bool>());
    EXPECT_EQ(entries["delta=24"].value("interrupted", false), true);
    EXPECT_FALSE(entries["delta=26"]["complete"].get<bool>());
    EXPECT_FALSE(entries["delta=26"].contains("interrupted"));
}

TEST(Batch, RefusesTheFolderOfASingleRun) {
    test::ScratchDir dir("batch-folder");
    const auto base = dir.write("base.toml", test::kCoarseParametricChute);
    dir.write("summary.json", "{}");
    const auto r = test::run_binary(
        dir, "batch --scenario '" + base + "' --sweep delta=20 --out '" + dir.file("") + "'");
    EXPECT_EQ(r.exit_code, 4);
    EXPECT_NE(r.err.find("single run"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace avalanche
