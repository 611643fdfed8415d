// Bad GIS inputs through the binary: the documented exit code (README.md), exactly one
// stderr line naming the file and what is wrong in it, and no summary.json or product
// left in the output folder (the folder itself may have been created: it is checked for
// writability before the inputs are read).
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "cli_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

using test::avaKot;
using test::run_binary;
using test::ScratchDir;

std::string shell_quoted(const std::string& s) { return "'" + s + "'"; }

// avaKot coarsened to 20 m once: every refusal happens before the time loop, so only the
// DEM loading costs anything.
class DemRefusals : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = std::make_unique<ScratchDir>("dem-refusals");
        dem_ = dir_->file("dem20.tif");
        ok_ = test::gdal_warp(avaKot("avaKot_dem.tif"), dem_, {"-tr", "20", "20", "-r", "average"});
    }
    static void TearDownTestSuite() { dir_.reset(); }
    void SetUp() override { ASSERT_TRUE(ok_); }

    // Runs `run` with the coarse DEM (unless `dem` is given) and the extra flags.
    static test::ProcessResult run(const std::string& out, const std::string& flags,
                                   const std::string& dem = "") {
        return run_binary(*dir_, "run --dem " + shell_quoted(dem.empty() ? dem_ : dem) + " --out " +
                                     shell_quoted(out) + " --t-end 1 " + flags);
    }
    static std::string file(const std::string& name) { return dir_->file(name); }
    static std::string release_flag() {
        return "--release " + shell_quoted(avaKot("avaKot_release.gpkg"));
    }

    static inline std::unique_ptr<ScratchDir> dir_;
    static inline std::string dem_;
    static inline bool ok_ = false;
};

// Exit code, one error line holding every needle, and nothing written into `out`.
void expect_refused(const test::ProcessResult& r, int code, const std::vector<std::string>& needles,
                    const std::string& out) {
    EXPECT_EQ(r.exit_code, code) << r.err;
    const auto lines = test::lines_of(r.err);
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_EQ(lines[0].rfind("avalanche-hazard: error: ", 0), 0u) << lines[0];
    for (const auto& n : needles)
        EXPECT_NE(lines[0].find(n), std::string::npos) << n << " in\n" << lines[0];
    std::error_code ec;
    if (!std::filesystem::exists(out, ec)) return;
    for (const auto& entry : std::filesystem::directory_iterator(out))
        ADD_FAILURE() << "left in the output folder: " << entry.path();
}

TEST_F(DemRefusals, DemWithoutCrs) {
    // An ESRI ASCII grid whose .prj went missing.
    const std::string asc = file("nocrs.asc");
    ASSERT_TRUE(test::gdal_translate(dem_, asc, {"-of", "AAIGrid"}));
    std::filesystem::remove(file("nocrs.prj"));
    const std::string out = file("out-nocrs");
    expect_refused(run(out, release_flag(), asc), 3, {asc, "coordinate reference system"}, out);
}

TEST_F(DemRefusals, ReleaseOutsideTheDem) {
    const std::string far = file("far.gpkg");
    ASSERT_TRUE(test::ogr2ogr(far, avaKot("avaKot_release.gpkg"),
                              {"-dialect", "sqlite", "-sql",
                               "SELECT ST_Translate(geom, 1e5, 1e5, 0) AS geom, thickness "
                               "FROM relKot",
                               "-nln", "far"}));
    const std::string out = file("out-far");
    expect_refused(run(out, "--release " + shell_quoted(far)), 3, {far, "outside the DEM"}, out);
}

TEST_F(DemRefusals, EmptyReleaseLayer) {
    const std::string empty = file("empty.gpkg");
    ASSERT_TRUE(test::ogr2ogr(empty, avaKot("avaKot_release.gpkg"), {"-where", "fid < 0"}));
    const std::string out = file("out-empty");
    expect_refused(run(out, "--release " + shell_quoted(empty)), 3, {empty, "no release polygon"},
                   out);
}

TEST_F(DemRefusals, SelfIntersectingPolygon) {
    // A bow-tie over the release area, in the DEM's CRS.
    const std::string bowtie = dir_->write("bowtie.geojson", R"({"type": "FeatureCollection",
 "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::31287"}},
 "features": [{"type": "Feature", "properties": {"thickness": 1.0},
  "geometry": {"type": "Polygon", "coordinates": [[[177780, 376630], [177890, 376830],
   [177890, 376630], [177780, 376830], [177780, 376630]]]}}]})");
    const std::string out = file("out-bowtie");
    expect_refused(run(out, "--release " + shell_quoted(bowtie)), 3, {bowtie, "invalid geometry"},
                   out);
}

TEST_F(DemRefusals, NonNumericThicknessField) {
    const std::string out = file("out-field");
    expect_refused(run(out, release_flag() + " --thickness-field Name"), 3,
                   {"avaKot_release.gpkg", "Name", "'KoT' is not a number"}, out);
}

TEST_F(DemRefusals, ShapefileWithoutShx) {
    const std::string shp = file("release.shp");
    ASSERT_TRUE(test::ogr2ogr(shp, avaKot("avaKot_release.gpkg"), {"-f", "ESRI Shapefile"}));
    ASSERT_TRUE(std::filesystem::remove(file("release.shx")));
    const std::string out = file("out-shx");
    expect_refused(run(out, "--release " + shell_quoted(shp)), 3, {shp, ".shx"}, out);
}

TEST_F(DemRefusals, MonitoringPointOutsideTheDem) {
    const std::string points =
        dir_->write("points.csv", "name,x,y\nvalley,178342.7,377698.9\nfar,0,0\n");
    const std::string out = file("out-points");
    expect_refused(run(out, release_flag() + " --points " + shell_quoted(points)), 3,
                   {points, "'far'", "outside the grid"}, out);
}

TEST_F(DemRefusals, BadMaterialAndNumericsFlags) {
    const std::string out = file("out-flags");
    expect_refused(run(out, release_flag() + " --delta 40 --phi 30"), 2, {"--delta"}, out);
    expect_refused(run(out, release_flag() + " --cfl 0.9"), 2, {"--cfl", "(0, 0.5]"}, out);
}

TEST_F(DemRefusals, ExistingResultsWithoutOverwrite) {
    const std::string out = file("out-existing");
    std::filesystem::create_directories(out);
    const std::string summary = "{\"from\": \"an earlier run\"}\n";
    dir_->write("out-existing/summary.json", summary);
    const auto r = run(out, release_flag());
    EXPECT_EQ(r.exit_code, 4) << r.err;
    const auto lines = test::lines_of(r.err);
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_NE(lines[0].find(out + ": already holds results"), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("--overwrite"), std::string::npos) << lines[0];
    EXPECT_EQ(test::read_text(out + "/summary.json"), summary);
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(out)) ++files;
    EXPECT_EQ(files, 1u) << "only the earlier summary.json";
}

}  // namespace
}  // namespace avalanche
