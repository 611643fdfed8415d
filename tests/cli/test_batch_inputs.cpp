// A resumed batch and its inputs (docs/batch.md, "Resuming"): the DEM or the release
// polygons replaced under the same path leave the configuration (and its hashes) as it
// was, so what tells the scenarios computed on the old inputs from current ones is the
// scene fingerprint their summary.json records; and the same inputs named from another
// folder, or moved, change only the paths, which the comparison leaves out.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "batch_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

namespace fs = std::filesystem;

double runout_of(const std::string& summary) {
    return test::read_json(summary)["runout"]["runout_length_m"].get<double>();
}

std::string fingerprint_of(const std::string& summary) {
    return test::read_json(summary).value("scene_fingerprint", "");
}

TEST(BatchInputs, ResumeRecomputesScenariosWhoseInputFilesChangedInPlace) {
    test::ScratchDir dir("batch-inputs");
    const std::string dem = dir.file("dem.tif"), release = dir.file("release.gpkg");
    ASSERT_TRUE(test::gdal_translate(test::avaKot("avaKot_dem.tif"), dem, {}));
    ASSERT_TRUE(test::ogr2ogr(release, test::avaKot("avaKot_release.gpkg"), {}));
    const auto base = dir.write("base.toml", "[terrain]\ntype = \"dem\"\ndem = \"" + dem +
                                                 "\"\n[release]\npolygons = \"" + release +
                                                 "\"\nthickness_field = \"thickness\"\n"
                                                 "[numerics]\ncell_size = 40.0\nt_end = 10.0\n"
                                                 "output_interval = 5.0\n");
    const std::string out = dir.file("out");
    const auto batch = [&] {
        return test::run_binary(
            dir, "batch --scenario '" + base + "' --sweep delta=25,30 --out '" + out + "'");
    };
    const std::string s25 = out + "/delta=25/summary.json", s30 = out + "/delta=30/summary.json";
    auto r = batch();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string first = fingerprint_of(s25);
    EXPECT_EQ(first.size(), 16u);
    EXPECT_EQ(fingerprint_of(s30), first);  // both scenarios run on one scene
    const double runout_first = runout_of(s25);
    auto kept = fs::last_write_time(s25);

    // The same inputs: both skipped.
    r = batch();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(fs::last_write_time(s25), kept);
    EXPECT_NE(r.err.find("and inputs " + first + " unchanged"), std::string::npos) << r.err;

    // The DEM replaced by one 30 % higher (steeper) under the same path: both recomputed,
    // on the new terrain.
    ASSERT_TRUE(test::gdal_translate(test::avaKot("avaKot_dem.tif"), dir.file("higher.tif"),
                                     {"-ot", "Float32", "-scale", "0", "1000", "0", "1300"}));
    fs::rename(dir.file("higher.tif"), dem);
    r = batch();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    for (const char* id : {"delta=25", "delta=30"})
        EXPECT_NE(r.err.find(std::string("computing ") + id + " (inputs changed"), std::string::npos)
            << r.err;
    const std::string second = fingerprint_of(s25);
    EXPECT_NE(second, first);
    EXPECT_EQ(fingerprint_of(s30), second);
    EXPECT_NE(runout_of(s25), runout_first);
    const auto csv = test::read_csv(out + "/comparison.csv");
    ASSERT_EQ(csv.size(), 3u);
    EXPECT_EQ(csv[1][0], "delta=25");
    EXPECT_EQ(std::stod(csv[1][2]), runout_of(s25));  // the comparison of the new runs

    // The release polygon moved 40 m in place (the DEM as it is now): recomputed again.
    ASSERT_TRUE(test::ogr2ogr(dir.file("moved.gpkg"), test::avaKot("avaKot_release.gpkg"),
                              {"-dialect", "sqlite", "-sql",
                               "SELECT ST_Translate(geom, 40, 0, 0) AS geom, thickness FROM relKot"}));
    fs::rename(dir.file("moved.gpkg"), release);
    r = batch();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("computing delta=25 (inputs changed"), std::string::npos) << r.err;
    EXPECT_NE(fingerprint_of(s25), second);

    // A summary written before the fingerprint was recorded: that scenario again, the
    // other one kept.
    auto summary = test::read_json(s30);
    summary.erase("scene_fingerprint");
    std::ofstream(s30) << summary.dump(2);
    kept = fs::last_write_time(s25);
    r = batch();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(fs::last_write_time(s25), kept);
    EXPECT_NE(r.err.find("computing delta=30 (its summary records no fingerprint"), std::string::npos)
        << r.err;
    EXPECT_EQ(fingerprint_of(s30), fingerprint_of(s25));
}

// The other side of the same rule: the configuration is compared without its input
// paths, which name the same files differently from another working folder, or after
// the inputs moved; their contents are compared through the fingerprint.
TEST(BatchInputs, ResumeSkipsScenariosWhoseInputsAreNamedFromAnotherFolderOrMoved) {
    test::ScratchDir dir("batch-paths");
    fs::create_directories(dir.file("project/inputs"));
    ASSERT_TRUE(test::gdal_translate(test::avaKot("avaKot_dem.tif"), dir.file("project/inputs/dem.tif"), {}));
    ASSERT_TRUE(test::ogr2ogr(dir.file("project/inputs/release.gpkg"), test::avaKot("avaKot_release.gpkg"), {}));
    const auto scenario = [&](const std::string& folder) {
        dir.write("project/base.toml", "[terrain]\ntype = \"dem\"\ndem = \"" + folder +
                                           "/dem.tif\"\n[release]\npolygons = \"" + folder +
                                           "/release.gpkg\"\nthickness_field = \"thickness\"\n"
                                           "[numerics]\ncell_size = 40.0\nt_end = 10.0\n"
                                           "output_interval = 5.0\n");
    };
    scenario("inputs");
    const std::string out = dir.file("project/out");
    const std::string s25 = out + "/delta=25/summary.json";
    // From the scratch folder: the inputs are named project/inputs/...
    const auto batch = [&] {
        return test::run_command(dir, "cd '" + dir.file("") + "' && '" + AVALANCHE_BINARY +
                                          "' batch --scenario project/base.toml --sweep delta=25,30 "
                                          "--out project/out");
    };
    auto r = batch();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto first = test::read_json(s25);
    const auto kept = fs::last_write_time(s25);
    const std::string hash = first.value("config_hash_without_paths", "");
    EXPECT_EQ(hash.size(), 16u);
    // The document must outlive the loop (a range-for over a member of a temporary reads
    // freed memory).
    const auto manifest = test::read_json(out + "/manifest.json");
    for (const auto& e : manifest["scenarios"]) {
        if (e["id"] == "delta=25") {
            EXPECT_EQ(e.value("config_hash_without_paths", ""), hash);
        }
    }

    // The same batch from the project folder (the inputs named inputs/..., another
    // configuration hash): skipped.
    r = test::run_command(dir, "cd '" + dir.file("project") + "' && '" + AVALANCHE_BINARY +
                                   "' batch --scenario base.toml --sweep delta=25,30 --out out");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(fs::last_write_time(s25), kept);
    EXPECT_NE(r.err.find("skipping delta=25"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("skipping delta=30"), std::string::npos) << r.err;

    // The inputs moved to another folder, unchanged, and the scenario file follows them.
    fs::rename(dir.file("project/inputs"), dir.file("project/terrain"));
    scenario("terrain");
    r = batch();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(fs::last_write_time(s25), kept);
    EXPECT_NE(r.err.find("skipping delta=25"), std::string::npos) << r.err;

    // A parameter changed: recomputed.
    dir.write("project/base.toml", test::read_text(dir.file("project/base.toml")) +
                                       "[output]\nh_threshold = 0.02\n");
    r = batch();
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("computing delta=25 (configuration changed)"), std::string::npos) << r.err;
    EXPECT_NE(test::read_json(s25).value("config_hash_without_paths", ""), hash);
}

}  // namespace
}  // namespace avalanche
