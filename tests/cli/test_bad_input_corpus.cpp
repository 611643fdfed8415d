// The bad-input corpus (tests/data/bad/README.md lists the same cases): every case runs
// the real binary and must give the documented exit code (README "Exit codes": 2 usage,
// 3 input, 4 output), exactly one stderr line that starts "avalanche-hazard: error: ",
// names the offending file, key or flag and says what is expected (case-specific
// substrings), and no product in the output folder (no .tif, .h5, .json, .csv, .png,
// .md beyond what was there before the run).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "bad_input_support.hpp"

namespace avalanche {
namespace {

namespace fs = std::filesystem;

struct BadInputCase {
    const char* id;    // test name
    const char* what;  // the refusal as the issue words it
    // The command line after the binary. Placeholders: {bad} tests/data/bad, {out} a fresh
    // output folder, {dem} {release} the good 20 m avaKot DEM and its release polygon,
    // {gen:NAME} an input made at run time (GeneratedInputs), {chute} a good chute
    // scenario.
    const char* args;
    int exit_code;
    std::vector<std::string> needles;  // in the error line; placeholders as in args
    const char* env = "";              // environment assignments for the run, if any
};

// A DEM run that is good apart from what the case adds.
#define DEM_RUN "run --dem {dem} --release {release} --t-end 1 --out {out} "
#define CHUTE_RUN(file) "run --scenario {bad}/" file " --out {out}"

// One row per case, as in the README table (long lines on purpose: one case, one glance).
// clang-format off
const std::vector<BadInputCase> kCases = {
    // ---- DEM rasters (exit 3)
    {"truncated_raster", "truncated raster", "run --dem {gen:truncated_dem} --release {release} --out {out}", 3,
     {"truncated.tif", "truncated or corrupt"}},
    {"corrupt_raster", "garbage bytes with a .tif name", "run --dem {bad}/garbage.tif --release {release} --out {out}", 3,
     {"garbage.tif", "not a readable raster"}},
    {"dem_without_crs", "DEM without CRS", "run --dem {bad}/dem_no_crs.asc --release {release} --out {out}", 3,
     {"dem_no_crs.asc", "no coordinate reference system", "EPSG"}},
    {"all_nodata_dem", "all-nodata DEM", "run --dem {bad}/dem_all_nodata.asc --crs EPSG:31287 --release {release} --out {out}", 3,
     {"dem_all_nodata.asc", "no valid elevation"}},
    {"all_nan_dem", "NaN elevations everywhere", "run --dem {gen:dem_all_nan} --release {release} --out {out}", 3,
     {"dem_all_nan.tif", "no valid elevation", "NaN"}},
    {"nan_under_release", "NaN elevations under the release", "run --dem {gen:dem_nan_release} --release {release} --out {out}", 3,
     {"avaKot_release.gpkg", "release cells lie on DEM voids"}},
    {"voids_under_release", "nodata voids under the release", "run --dem {gen:dem_void_release} --release {release} --out {out}", 3,
     {"avaKot_release.gpkg", "release cells lie on DEM voids"}},
    {"dem_too_large", "a header declaring 200000 x 200000 cells", "run --dem {bad}/dem_too_large.vrt --release {release} --out {out}", 3,
     {"dem_too_large.vrt", "200000 x 200000", "GiB", "cell_size"}},
    {"cell_size_too_small", "a tiny cell size on a real DEM", DEM_RUN "--cell-size 0.001", 3,
     {"dem20.tif", "GiB of solver state", "larger cell size"}},
    {"dem_missing", "nonexistent DEM path", "run --dem {bad}/no_such_dem.tif --release {release} --out {out}", 3,
     {"no_such_dem.tif", "file not found"}},
    // ---- release areas (exit 3)
    {"polygon_outside_dem", "polygons outside the DEM", "run --dem {dem} --release {bad}/release_outside.geojson --out {out}", 3,
     {"release_outside.geojson", "outside the DEM"}},
    {"self_intersecting_polygon", "self-intersecting polygon", "run --dem {dem} --release {bad}/release_self_intersecting.geojson --out {out}", 3,
     {"release_self_intersecting.geojson", "invalid geometry", "self-intersecting"}},
    {"empty_layer", "empty layer", "run --dem {dem} --release {bad}/release_empty_layer.geojson --out {out}", 3,
     {"release_empty_layer.geojson", "no release polygon"}},
    {"empty_polygon", "empty polygon", "run --dem {dem} --release {bad}/release_empty_polygon.geojson --out {out}", 3,
     {"release_empty_polygon.geojson", "feature 0", "no geometry"}},
    {"release_without_polygons", "release file without polygons (points)", "run --dem {dem} --release {bad}/release_points_only.geojson --out {out}", 3,
     {"release_points_only.geojson", "POINT", "must be polygons"}},
    {"shapefile_without_shx", "Shapefile missing its .shx", "run --dem {dem} --release {gen:shp_without_shx} --thickness 1 --out {out}", 3,
     {"release.shp", "release.shx", "missing"}},
    {"shapefile_without_dbf", "Shapefile missing its .dbf", "run --dem {dem} --release {gen:shp_without_dbf} --thickness 1 --out {out}", 3,
     {"release.shp", "release.dbf", "missing"}},
    {"non_numeric_thickness", "non-numeric thickness attribute", "run --dem {dem} --release {bad}/release_text_thickness.geojson --out {out}", 3,
     {"release_text_thickness.geojson", "field 'thickness'", "'two metres' is not a number"}},
    {"negative_thickness_attribute", "negative thickness attribute", "run --dem {dem} --release {bad}/release_negative_thickness.geojson --out {out}", 3,
     {"release_negative_thickness.geojson", "field 'thickness'", "expected a positive"}},
    {"thickness_raster_wrong_crs", "thickness raster in another CRS, off the DEM", "run --dem {dem} --release {gen:thickness_wrong_crs} --out {out}", 3,
     {"thickness_epsg32632.tif", "no release thickness on the grid"}},
    {"thickness_raster_negative", "thickness raster with negative cells", "run --dem {dem} --release {gen:thickness_negative} --out {out}", 3,
     {"thickness_negative.tif", "negative release thickness"}},
    {"release_missing", "nonexistent release file", "run --dem {dem} --release {bad}/no_such_release.gpkg --out {out}", 3,
     {"no_such_release.gpkg", "file not found"}},
    // ---- monitoring points (exit 3)
    {"points_missing_column", "point CSV without a y column", DEM_RUN "--points {bad}/points_missing_column.csv", 3,
     {"points_missing_column.csv", "line 1", "name,x,y"}},
    {"points_non_numeric", "non-numeric coordinate", DEM_RUN "--points {bad}/points_non_numeric.csv", 3,
     {"points_non_numeric.csv", "line 3", "must be numbers", "17833O.5"}},
    {"point_outside_dem", "point outside the DEM", DEM_RUN "--points {bad}/points_outside.csv", 3,
     {"points_outside.csv", "'far'", "outside the grid"}},
    {"point_name_with_slash", "point name that cannot name an HDF5 group", DEM_RUN "--points {bad}/points_name_slash.geojson", 3,
     {"points_name_slash.geojson", "feature 1", "'Lift A/B'", "without '/'"}},
    // ---- flags on a DEM run (exit 2: the flag is named)
    {"negative_thickness_flag", "negative thickness", DEM_RUN "--thickness -1", 2,
     {"--thickness", "positive thickness"}},
    {"non_positive_cell_size_flag", "non-positive cell size", DEM_RUN "--cell-size -5", 2,
     {"--cell-size", "cell size >= 0"}},
    {"angle_above_90_flag", "angle >= 90", DEM_RUN "--phi 95", 2, {"--phi", "(0, 90)"}},
    // ---- scenario files (exit 2 for values, 3 for the file itself)
    {"unknown_scenario_key", "unknown scenario key", CHUTE_RUN("scenario_unknown_key.toml"), 2,
     {"scenario_unknown_key.toml", "material.mu", "unknown key", "phi_deg"}},
    {"unknown_scenario_table", "unknown scenario table", CHUTE_RUN("scenario_unknown_table.toml"), 2,
     {"scenario_unknown_table.toml", "solver", "unknown table"}},
    {"string_for_number", "mistyped value (string for number)", CHUTE_RUN("scenario_string_for_number.toml"), 2,
     {"scenario_string_for_number.toml", "numerics.t_end", "expected a number, got a string"}},
    {"malformed_toml", "malformed TOML", CHUTE_RUN("scenario_malformed.toml"), 3,
     {"scenario_malformed.toml", "line 16", "parsing floating-point"}},
    {"parse_error_quoting_a_newline", "malformed TOML whose error quotes a newline", CHUTE_RUN("scenario_error_quotes_newline.toml"), 3,
     {"scenario_error_quotes_newline.toml", "line 4", "saw 'i\\n'"}},
    {"empty_scenario", "empty scenario file", CHUTE_RUN("scenario_empty.toml"), 2,
     {"scenario_empty.toml", "terrain.type", "missing"}},
    {"delta_above_phi", "delta > phi", CHUTE_RUN("scenario_delta_above_phi.toml"), 2,
     {"scenario_delta_above_phi.toml", "material.delta_deg", "delta <= phi"}},
    {"phi_90", "angle >= 90", CHUTE_RUN("scenario_phi_90.toml"), 2,
     {"scenario_phi_90.toml", "material.phi_deg", "(0, 90)"}},
    {"negative_delta", "negative angle", CHUTE_RUN("scenario_negative_delta.toml"), 2,
     {"scenario_negative_delta.toml", "material.delta_deg", "[0, 90)"}},
    {"courant_above_half", "Courant above 0.5", CHUTE_RUN("scenario_courant.toml"), 2,
     {"scenario_courant.toml", "numerics.cfl", "(0, 0.5]"}},
    {"zero_t_end", "non-positive t_end", CHUTE_RUN("scenario_zero_t_end.toml"), 2,
     {"scenario_zero_t_end.toml", "numerics.t_end", "positive end time"}},
    {"negative_output_interval", "non-positive output interval", CHUTE_RUN("scenario_negative_output_interval.toml"), 2,
     {"scenario_negative_output_interval.toml", "numerics.output_interval", "positive interval"}},
    {"zero_cell_size_chute", "non-positive cell size", CHUTE_RUN("scenario_zero_cell_size.toml"), 2,
     {"scenario_zero_cell_size.toml", "numerics.cell_size", "positive cell size"}},
    {"negative_release_thickness", "negative thickness", CHUTE_RUN("scenario_negative_thickness.toml"), 2,
     {"scenario_negative_thickness.toml", "release.thickness", "positive"}},
    {"bad_choice", "unknown choice", CHUTE_RUN("scenario_bad_choice.toml"), 2,
     {"scenario_bad_choice.toml", "numerics.scheme", "\"waf\", \"godunov\""}},
    {"chute_too_large", "a chute grid too large for the memory", CHUTE_RUN("scenario_chute_too_large.toml"), 2,
     {"scenario_chute_too_large.toml", "numerics.cell_size", "1000000 x 1000000 chute grid", "GiB"}},
    {"scenario_missing", "nonexistent scenario file", CHUTE_RUN("no_such_scenario.toml"), 3,
     {"no_such_scenario.toml", "cannot open the scenario file"}},
    {"non_numeric_flag", "string for a number on the command line", "run --scenario {chute} --out {out} --t-end soon", 2,
     {"--t-end", "soon"}},
    {"malformed_memory_override", "malformed memory override", "run --dem {dem} --release {release} --out {out}", 2,
     {"AVALANCHE_MAX_MEMORY_GB", "positive number of GiB", "'lots'"}, "AVALANCHE_MAX_MEMORY_GB=lots"},
    {"dem_above_memory_override", "DEM above the memory override", "run --dem {dem} --release {release} --out {out}", 3,
     {"dem20.tif", "110 x 129 grid", "0.001 GiB of memory allowed by AVALANCHE_MAX_MEMORY_GB"},
     "AVALANCHE_MAX_MEMORY_GB=0.001"},
    // ---- output folder (exit 4)
    {"output_is_a_file", "output folder is an existing file", "run --scenario {chute} --out {gen:a_file}", 4,
     {"a-file", "exists and is not a folder"}},
    {"output_not_writable", "unwritable output folder", "run --scenario {chute} --out {gen:read_only}", 4,
     {"{gen:read_only}", "output folder"}},
    {"output_holds_results", "output exists without --overwrite", "run --scenario {chute} --out {gen:old_results}", 4,
     {"old-results", "already holds results", "--overwrite"}},
};
// clang-format on

// gtest names a failing parameter by this, instead of a hex dump.
void PrintTo(const BadInputCase& c, std::ostream* os) { *os << c.id; }

std::string replaced_all(std::string text, const std::string& from, const std::string& to) {
    for (auto pos = text.find(from); pos != std::string::npos;
         pos = text.find(from, pos + to.size()))
        text.replace(pos, from.size(), to);
    return text;
}

bool is_product(const fs::path& p) {
    static const std::set<std::string> kProducts{".tif", ".h5", ".json", ".csv",
                                                 ".png", ".md", ".qml",  ".part"};
    return kProducts.count(p.extension().string()) > 0;
}

// Product files below `dir` with their sizes ("" when dir does not exist or is not a
// folder).
std::map<std::string, std::uintmax_t> products_in(const std::string& dir) {
    std::map<std::string, std::uintmax_t> out;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return out;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec))
        if (e.is_regular_file() && is_product(e.path())) out[e.path().string()] = e.file_size();
    return out;
}

class BadInputCorpus : public ::testing::TestWithParam<BadInputCase> {
  protected:
    // ctest runs every case in its own process: the inputs are made once per process.
    static void SetUpTestSuite() {
        dir_ = std::make_unique<test::ScratchDir>("bad-input-corpus");
        gen_ = test::make_generated_inputs(*dir_);
    }
    static void TearDownTestSuite() {
        if (!gen_.read_only.empty()) ::chmod(gen_.read_only.c_str(), 0755);
        dir_.reset();
    }

    static std::string expand(std::string text, const std::string& out) {
        const std::map<std::string, std::string> generated{
            {"truncated_dem", gen_.truncated_dem},
            {"dem_nan_release", gen_.dem_nan_release},
            {"dem_void_release", gen_.dem_void_release},
            {"dem_all_nan", gen_.dem_all_nan},
            {"shp_without_shx", gen_.shp_without_shx},
            {"shp_without_dbf", gen_.shp_without_dbf},
            {"thickness_wrong_crs", gen_.thickness_wrong_crs},
            {"thickness_negative", gen_.thickness_negative},
            {"a_file", gen_.a_file},
            {"old_results", gen_.old_results},
            {"read_only", gen_.read_only}};
        for (const auto& [name, path] : generated)
            text = replaced_all(text, "{gen:" + name + "}", path);
        text = replaced_all(text, "{bad}", std::string(AVALANCHE_TEST_DATA_DIR) + "/bad");
        text = replaced_all(text, "{dem}", gen_.dem);
        text = replaced_all(text, "{release}", test::avaKot("avaKot_release.gpkg"));
        text = replaced_all(text, "{chute}", gen_.good_chute);
        return replaced_all(text, "{out}", out);
    }

    static inline std::unique_ptr<test::ScratchDir> dir_;
    static inline test::GeneratedInputs gen_;
};

TEST_P(BadInputCorpus, IsRefusedWithOneLineAndNoProducts) {
    ASSERT_TRUE(gen_.ok) << "could not make the generated inputs in " << dir_->path();
    const BadInputCase& c = GetParam();
    const std::string out = dir_->file(std::string("out-") + c.id);
    const std::string args = expand(c.args, out);
    const std::string target = args.substr(args.find("--out ") + 6);
    const std::string out_dir = target.substr(0, target.find(' '));
    const auto before = products_in(out_dir);

    const test::ProcessResult r = test::run_binary_with_env(*dir_, c.env, args);

    SCOPED_TRACE(std::string(c.id) + " (" + c.what + "): " + args);
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    const auto lines = test::lines_of(r.err);
    ASSERT_EQ(lines.size(), 1u) << "stderr:\n" << r.err;
    EXPECT_EQ(lines[0].rfind("avalanche-hazard: error: ", 0), 0u) << lines[0];
    for (const auto& needle : c.needles) {
        const std::string n = expand(needle, out);
        EXPECT_NE(lines[0].find(n), std::string::npos) << "'" << n << "' in\n" << lines[0];
    }
    EXPECT_EQ(products_in(out_dir), before) << "the run left or changed products in " << out_dir;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInputCorpus, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<BadInputCase>& info) {
                             return std::string(info.param.id);
                         });

// A full disk, simulated by a file-size limit on the child (RLIMIT_FSIZE, EFBIG): once
// while results.h5 is written (16 KiB) and once while the last products are (100 KiB:
// results.h5 and the maps fit, the report does not). Either way: exit 4, one line naming
// a file in the output folder, no summary.json (its presence says a run is complete),
// and every file left under a final name whole (each GeoTIFF reads back in full); only
// *.part files may be unfinished.
TEST_F(BadInputCorpus, FullDiskIsAnOutputErrorAndLeavesNoCompleteLookingRun) {
    ASSERT_TRUE(gen_.ok);
    for (const rlim_t limit : {rlim_t{16} << 10, rlim_t{100} << 10}) {
        const std::string out = dir_->file("out-full-disk-" + std::to_string(limit));
        const auto r = test::run_binary_with_file_limit(
            *dir_,
            {"run", "--dem", gen_.dem, "--release", test::avaKot("avaKot_release.gpkg"), "--t-end",
             "2", "--out", out},
            limit);
        SCOPED_TRACE("file size limit " + std::to_string(limit) + " B");
        EXPECT_EQ(r.exit_code, 4) << r.err;
        const auto lines = test::lines_of(r.err);
        ASSERT_FALSE(lines.empty());
        const std::string& error = lines.back();
        EXPECT_EQ(error.rfind("avalanche-hazard: error: " + out + "/", 0), 0u) << r.err;
        // (The run's caveats -- a 2 s run has not stopped -- are logged as warnings.)
        for (std::size_t k = 0; k + 1 < lines.size(); ++k)
            EXPECT_TRUE(lines[k].rfind("info: ", 0) == 0 || lines[k].rfind("warning: ", 0) == 0)
                << "only log lines before the error:\n"
                << r.err;
        EXPECT_FALSE(fs::exists(out + "/summary.json"));
        for (const auto& e : fs::directory_iterator(out)) {
            if (e.path().extension() != ".tif") continue;
            const test::Raster raster = test::read_raster(e.path().string());
            EXPECT_EQ(raster.values.size(), static_cast<std::size_t>(raster.width) * raster.height)
                << e.path();
        }
    }
}

// The corpus table in tests/data/bad/README.md lists exactly these cases.
TEST(BadInputCorpusTable, ReadmeListsEveryCase) {
    const std::string readme =
        test::read_text(std::string(AVALANCHE_TEST_DATA_DIR) + "/bad/README.md");
    ASSERT_FALSE(readme.empty());
    for (const auto& c : kCases)
        EXPECT_NE(readme.find(std::string("`") + c.id + "`"), std::string::npos) << c.id;
    EXPECT_NE(readme.find("`full_disk`"), std::string::npos);
    EXPECT_GE(kCases.size(), 30u);
}

}  // namespace
}  // namespace avalanche
