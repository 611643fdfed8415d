// `batch` built on run's scenario flags (--dem, --release, --delta, ...) instead of a
// scenario file (docs/batch.md, "The base scenario"): the scenarios are those of the
// equivalent file, a swept parameter's values win over its flag (and the batch says so),
// and the comparison and the manifest name the flags where they would name the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "batch_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

namespace fs = std::filesystem;

TEST(BatchFlags, DemAndReleaseFlagsGiveTheScenariosOfTheEquivalentFile) {
    test::ScratchDir dir("batch-flags");
    const std::string dem = test::avaKot("avaKot_dem.tif");
    const std::string release = test::avaKot("avaKot_release.gpkg");
    const auto base = dir.write("base.toml", "[terrain]\ntype = \"dem\"\ndem = \"" + dem +
                                                 "\"\n[release]\npolygons = \"" + release +
                                                 "\"\nthickness_field = \"thickness\"\n"
                                                 "[numerics]\ncell_size = 40.0\nt_end = 10.0\n"
                                                 "output_interval = 5.0\n");
    const std::string from_file = dir.file("from_file"), from_flags = dir.file("from_flags");
    auto r = test::run_binary(dir, "batch --scenario '" + base +
                                       "' --sweep delta=25,30 --out '" + from_file + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // --delta 22 is the base's; the sweep sets delta in every scenario.
    const std::string flags = "--dem " + dem + " --release " + release +
                              " --thickness-field thickness --delta 22 --cell-size 40 --t-end 10 "
                              "--output-interval 5";
    r = test::run_binary(dir, "batch " + flags + " --sweep delta=25,30 --out '" + from_flags + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("--delta replaced in every scenario by the sweep's values"),
              std::string::npos)
        << r.err;

    // The same scenarios: every column of the comparison but the wall time, and the
    // prepared scene, are equal.
    const auto a = test::read_csv(from_file + "/comparison.csv");
    const auto b = test::read_csv(from_flags + "/comparison.csv");
    ASSERT_EQ(a.size(), 3u);
    ASSERT_EQ(b.size(), a.size());
    ASSERT_EQ(a[0].back(), "wall_s");
    for (std::size_t row = 0; row < a.size(); ++row) {
        ASSERT_EQ(b[row].size(), a[row].size());
        for (std::size_t col = 0; col + 1 < a[row].size(); ++col)
            EXPECT_EQ(b[row][col], a[row][col]) << a[0][col] << " of row " << row;
    }
    EXPECT_NE(a[1][2], a[2][2]);  // the runouts of delta 25 and 30 differ: the sweep acted
    for (const char* id : {"delta=25", "delta=30"}) {
        const auto fa = test::read_json(from_file + "/" + id + "/summary.json");
        const auto fb = test::read_json(from_flags + "/" + id + "/summary.json");
        EXPECT_EQ(fb.at("scene_fingerprint"), fa.at("scene_fingerprint")) << id;
    }

    // Named where the file would be.
    const auto batch = test::read_json(from_flags + "/manifest.json").at("batch");
    EXPECT_TRUE(batch.at("base_scenario").is_null());
    EXPECT_EQ(batch.at("base_flags").get<std::string>(), flags);
    EXPECT_EQ(test::read_json(from_file + "/manifest.json").at("batch").at("base_flags"), "");
    EXPECT_NE(test::read_text(from_flags + "/comparison.md").find("Base scenario: `" + flags + "`"),
              std::string::npos);

    // Run again: both scenarios complete with the same configuration, so both are skipped.
    const auto kept = fs::last_write_time(from_flags + "/delta=25/summary.json");
    r = test::run_binary(dir, "batch " + flags + " --sweep delta=25,30 --out '" + from_flags + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(fs::last_write_time(from_flags + "/delta=25/summary.json"), kept);
}

TEST(BatchFlags, WithoutAScenarioFileADemAndAReleaseAreRequired) {
    test::ScratchDir dir("batch-flags-refused");
    const std::string out = dir.file("out");
    auto r = test::run_binary(dir, "batch --sweep delta=20,25 --out '" + out + "'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--scenario: expected a scenario file, or --dem and --release"),
              std::string::npos)
        << r.err;
    r = test::run_binary(dir, "batch --dem '" + test::avaKot("avaKot_dem.tif") +
                                  "' --sweep delta=20,25 --out '" + out + "'");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("--release: required with --dem"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace avalanche
