// The GIS pipeline end to end through the binary (issue "GIS pipeline", "What it must
// show"): an ASTER-like geographic DEM in two tiles with a release polygon in a third CRS
// gives UTM products; and the values inside the products agree with each other, with
// summary.json, monitoring.csv and report.md. Grids are coarse (20-30 m) and runs short
// (30-40 s simulated), so each run takes about a second.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <set>
#include <sstream>

#include "cli_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

using test::avaKot;
using test::Raster;
using test::read_json_file;
using test::read_raster;
using test::run_binary;
using test::ScratchDir;

const std::vector<std::string> kMaps = {"max_depth",    "max_velocity",      "max_pressure",
                                        "arrival_time", "deposit_thickness", "hazard_class"};

std::string shell_quoted(const std::string& s) { return "'" + s + "'"; }

// Cells of `r` whose centre lies inside `polygon`: the release rule (cell-centre).
std::vector<std::pair<int, int>> cells_inside(const Raster& r, const OGRGeometry& polygon) {
    std::vector<std::pair<int, int>> cells;
    for (int row = 0; row < r.height; ++row)
        for (int col = 0; col < r.width; ++col) {
            const auto c = r.centre(col, row);
            const OGRPoint p(c[0], c[1]);
            if (polygon.Contains(&p)) cells.emplace_back(col, row);
        }
    return cells;
}

// Slope angle (rad) of `dem` at an interior cell, by central differences.
double slope_at(const Raster& dem, int col, int row) {
    const double dzdx = (dem.at(col + 1, row) - dem.at(col - 1, row)) / (2.0 * dem.gt[1]);
    const double dzdy = (dem.at(col, row - 1) - dem.at(col, row + 1)) / (2.0 * -dem.gt[5]);
    return std::atan(std::hypot(dzdx, dzdy));
}

TEST(DemPipeline, AsterLikeTilesAndReprojectedReleaseGiveCompleteUtmProducts) {
    ScratchDir dir("aster");
    // ASTER GDEM look-alike: 1 arc-second, EPSG:4326, Int16 with -9999 voids, two tiles.
    const std::string aster = dir.file("aster.tif");
    ASSERT_TRUE(test::gdal_warp(avaKot("avaKot_dem.tif"), aster,
                                {"-t_srs", "EPSG:4326", "-tr", "0.000277777777778",
                                 "0.000277777777778", "-ot", "Int16", "-dstnodata", "-9999"}));
    const Raster whole = read_raster(aster);
    const int half = whole.height / 2;
    const std::string north = dir.file("tile_n.tif"), south = dir.file("tile_s.tif");
    ASSERT_TRUE(test::gdal_translate(
        aster, north, {"-srcwin", "0", "0", std::to_string(whole.width), std::to_string(half)}));
    ASSERT_TRUE(
        test::gdal_translate(aster, south,
                             {"-srcwin", "0", std::to_string(half), std::to_string(whole.width),
                              std::to_string(whole.height - half)}));
    // The release in Web Mercator: neither the DEM's CRS nor the grid's.
    const std::string release = dir.file("release.geojson");
    ASSERT_TRUE(test::ogr2ogr(release, avaKot("avaKot_release.gpkg"),
                              {"-f", "GeoJSON", "-t_srs", "EPSG:3857"}));

    const std::string out = dir.file("out");
    const auto r = run_binary(dir, "run --dem " + shell_quoted(north) + " --dem " +
                                       shell_quoted(south) + " --release " + shell_quoted(release) +
                                       " --thickness 2 --t-end 30 --out " + shell_quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;

    std::vector<std::string> tifs = kMaps;
    tifs.push_back("dem");
    for (const auto& name : tifs) {
        SCOPED_TRACE(name);
        const Raster map = read_raster(out + "/" + name + ".tif");
        EXPECT_EQ(map.epsg, "32632") << "Tyrol at 10.4 E is UTM zone 32N";
        EXPECT_TRUE(map.has_nodata);
        std::size_t nan = 0, valid = 0;
        for (double v : map.values) {
            nan += std::isnan(v) ? 1 : 0;
            valid += (!std::isnan(v) && v != map.nodata) ? 1 : 0;
        }
        EXPECT_EQ(nan, 0u);
        EXPECT_GT(valid, 0u);
        if (name != "dem") {
            EXPECT_TRUE(std::filesystem::exists(out + "/" + name + ".qml"));
        }
    }

    const auto s = read_json_file(out + "/summary.json");
    EXPECT_LT(std::abs(s["volume"]["relative_error"].get<double>()), 1e-12);
    // Independent volume: bed-normal thickness x polygon area (OGR, in UTM) / cos(slope),
    // the slope averaged over the release cells of the written dem.tif.
    const auto polygon = test::first_polygon(avaKot("avaKot_release.gpkg"), 32632);
    ASSERT_NE(polygon, nullptr);
    const double area = polygon->toPolygon()->get_Area();
    const Raster dem = read_raster(out + "/dem.tif");
    const auto release_cells = cells_inside(dem, *polygon);
    ASSERT_FALSE(release_cells.empty());
    double mean_slope = 0.0;
    for (const auto& [col, row] : release_cells) mean_slope += slope_at(dem, col, row);
    mean_slope /= static_cast<double>(release_cells.size());
    const double expected = 2.0 * area / std::cos(mean_slope);
    const double released = s["volume"]["released_m3"].get<double>();
    EXPECT_GT(released, 0.0);
    EXPECT_NEAR(released / expected, 1.0, 0.2) << "expected " << expected << " m3";

    EXPECT_GT(s["runout"]["runout_length_m"].get<double>(), 0.0);
    const double alpha = s["runout"]["travel_angle_deg"].get<double>();
    EXPECT_GT(alpha, 5.0);
    EXPECT_LT(alpha, 60.0);
}

// Snow density and hazard limits chosen so that this short run's pressures (tens to
// thousands of kPa) fall into all three classes: the class test then sees every branch.
constexpr double kDensity = 300.0;
constexpr double kLowKpa = 100.0, kHighKpa = 1000.0;

// One run on avaKot at 20 m with its monitoring point, shared by the value checks; a
// scenario file, as a planner would write it, so that the [output] keys are exercised.
class DemProducts : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir_ = std::make_unique<ScratchDir>("dem-values");
        out_ = dir_->file("out");
        std::ostringstream toml;
        toml << "[terrain]\ntype = \"dem\"\ndem = \"" << avaKot("avaKot_dem.tif")
             << "\"\n[release]\npolygons = \"" << avaKot("avaKot_release.gpkg")
             << "\"\nthickness_field = \"thickness\"\n[points]\nfile = \""
             << avaKot("avaKot_points.gpkg") << "\"\n[material]\ndensity = " << kDensity
             << "\n[numerics]\ncell_size = 20.0\nt_end = 40.0\n[output]\npressure_low_kpa = "
             << kLowKpa << "\npressure_high_kpa = " << kHighKpa << "\n";
        const std::string scenario = dir_->write("scenario.toml", toml.str());
        run_ = run_binary(
            *dir_, "run --scenario " + shell_quoted(scenario) + " --out " + shell_quoted(out_));
    }
    static void TearDownTestSuite() { dir_.reset(); }
    void SetUp() override { ASSERT_EQ(run_.exit_code, 0) << run_.err; }
    static Raster map(const std::string& name) { return read_raster(out_ + "/" + name + ".tif"); }

    static inline std::unique_ptr<ScratchDir> dir_;
    static inline std::string out_;
    static inline test::ProcessResult run_;
};

TEST_F(DemProducts, MaxDepthBoundsTheDepositWhereBothAreValid) {
    const Raster depth = map("max_depth"), deposit = map("deposit_thickness");
    std::size_t both = 0;
    for (int row = 0; row < depth.height; ++row)
        for (int col = 0; col < depth.width; ++col) {
            if (!deposit.valid(col, row)) continue;
            // The deposit is thicker than the threshold somewhere it was reached...
            if (deposit.at(col, row) >= 0.01) {
                EXPECT_TRUE(depth.valid(col, row));
            }
            if (!depth.valid(col, row)) continue;
            ++both;
            EXPECT_GE(depth.at(col, row), deposit.at(col, row)) << col << ", " << row;
        }
    EXPECT_GT(both, 0u);
}

TEST_F(DemProducts, HazardClassFollowsThePressureThresholds) {
    const Raster depth = map("max_depth"), pressure = map("max_pressure"),
                 classes = map("hazard_class");
    ASSERT_TRUE(classes.has_nodata);
    int counts[4] = {0, 0, 0, 0};
    for (int row = 0; row < depth.height; ++row)
        for (int col = 0; col < depth.width; ++col) {
            const double c = classes.at(col, row);
            ASSERT_TRUE(c == 0 || c == 1 || c == 2 || c == 3) << c;
            ++counts[static_cast<int>(c)];
            EXPECT_EQ(pressure.valid(col, row), depth.valid(col, row));
            if (!depth.valid(col, row)) {
                EXPECT_EQ(c, 0) << "not reached: " << col << ", " << row;
                continue;
            }
            const double p = pressure.at(col, row);
            // float32 storage: skip the rare cell within rounding of a limit.
            if (std::abs(p / kHighKpa - 1.0) < 1e-6 || std::abs(p / kLowKpa - 1.0) < 1e-6) continue;
            const int expected = p >= kHighKpa ? 3 : p >= kLowKpa ? 2 : 1;
            EXPECT_EQ(c, expected) << "p = " << p << " kPa at " << col << ", " << row;
        }
    for (int c = 0; c < 4; ++c) EXPECT_GT(counts[c], 0) << "class " << c;
}

TEST_F(DemProducts, ArrivalTimeIsValidWhereReachedAndZeroExactlyOnTheRelease) {
    const Raster depth = map("max_depth"), arrival = map("arrival_time");
    ASSERT_LT(depth.gt[5], 0.0) << "north-up: row 0 is the northern row";
    const auto polygon = test::first_polygon(avaKot("avaKot_release.gpkg"));
    ASSERT_NE(polygon, nullptr);
    const auto release = cells_inside(depth, *polygon);
    ASSERT_GT(release.size(), 10u);
    std::set<std::pair<int, int>> release_set(release.begin(), release.end());
    for (int row = 0; row < depth.height; ++row)
        for (int col = 0; col < depth.width; ++col) {
            ASSERT_EQ(arrival.valid(col, row), depth.valid(col, row)) << col << ", " << row;
            // A map flipped north-south would put the zeros on the mirrored rows.
            const bool zero = arrival.valid(col, row) && arrival.at(col, row) == 0.0;
            EXPECT_EQ(zero, release_set.count({col, row}) == 1) << col << ", " << row;
        }
}

TEST_F(DemProducts, PressureIsDensityTimesSpeedSquared) {
    const Raster speed = map("max_velocity"), pressure = map("max_pressure");
    std::size_t checked = 0;
    for (int row = 0; row < speed.height; ++row)
        for (int col = 0; col < speed.width; ++col) {
            ASSERT_EQ(speed.valid(col, row), pressure.valid(col, row));
            if (!speed.valid(col, row)) continue;
            const double v = speed.at(col, row), p = pressure.at(col, row);
            EXPECT_NEAR(p, kDensity * v * v / 1000.0, 1e-5 * std::max(p, 1e-3));
            ++checked;
        }
    EXPECT_GT(checked, 0u);
}

TEST_F(DemProducts, MonitoringSeriesAndSummaryAgreeWithTheMaps) {
    const auto lines = test::lines_of(test::read_text(out_ + "/monitoring.csv"));
    ASSERT_GT(lines.size(), 2u);
    EXPECT_EQ(lines[0], "point,x,y,t_s,h_m,u_ms,v_ms,speed_ms,pressure_kpa");
    double previous_t = -1.0, max_h = 0.0;
    for (std::size_t k = 1; k < lines.size(); ++k) {
        std::vector<std::string> cells;
        std::stringstream row(lines[k]);
        for (std::string c; std::getline(row, c, ',');) cells.push_back(c);
        ASSERT_EQ(cells.size(), 9u) << lines[k];
        const double t = std::stod(cells[3]);
        EXPECT_GT(t, previous_t) << "line " << k + 1;
        previous_t = t;
        max_h = std::max(max_h, std::stod(cells[4]));
        // Below the maps' h_thr (1 cm) the layer is the film a flow leaves: no velocity,
        // speed or pressure (docs/products.md, "Monitoring points").
        if (std::stod(cells[4]) < 0.01) {
            for (int c = 5; c <= 8; ++c) {
                EXPECT_EQ(std::stod(cells[c]), 0.0) << "line " << k + 1;
            }
        }
    }

    const auto s = read_json_file(out_ + "/summary.json");
    ASSERT_EQ(s["monitoring_points"].size(), 1u);
    const auto& point = s["monitoring_points"][0];
    const double summary_depth = point["max_depth_m"].get<double>();
    ASSERT_GE(summary_depth, 0.01) << "the point must be reached for the check to mean anything";
    const Raster depth = map("max_depth");
    int col = 0, row = 0;
    ASSERT_TRUE(depth.cell_of(point["x"].get<double>(), point["y"].get<double>(), col, row));
    ASSERT_TRUE(depth.valid(col, row));
    EXPECT_NEAR(depth.at(col, row), summary_depth, 1e-6 * summary_depth);  // float32 map
    EXPECT_LE(max_h, summary_depth * (1.0 + 1e-9)) << "samples cannot exceed the maximum";
    EXPECT_GT(max_h, 0.0);
}

TEST_F(DemProducts, ReportQuotesTheRunoutLengthOfTheSummary) {
    const auto s = read_json_file(out_ + "/summary.json");
    std::ostringstream length;
    length << std::fixed << std::setprecision(1) << s["runout"]["runout_length_m"].get<double>();
    const std::string report = test::read_text(out_ + "/report.md");
    EXPECT_NE(report.find("| " + length.str() + " m |"), std::string::npos) << length.str();
    // avaKot's DEM covers 60 % of its grid: the maps' hatch is explained.
    EXPECT_NE(report.find("hatched with diagonals is outside the DEM's data"), std::string::npos);
}

TEST_F(DemProducts, ComputationalDemIsNorthUpLikeTheSource) {
    // dem.tif against the 5 m source at the same map points: a north-south flip would be
    // hundreds of metres off on this valley.
    const Raster dem = map("dem"), source = read_raster(avaKot("avaKot_dem.tif"));
    double direct = 0.0, flipped = 0.0;
    int n = 0;
    for (int row = 1; row + 1 < dem.height; ++row)
        for (int col = 0; col < dem.width; ++col) {
            const auto c = dem.centre(col, row);
            int sc = 0, sr = 0;
            if (!source.cell_of(c[0], c[1], sc, sr) || !source.valid(sc, sr)) continue;
            direct += std::abs(dem.at(col, row) - source.at(sc, sr));
            flipped += std::abs(dem.at(col, dem.height - 1 - row) - source.at(sc, sr));
            ++n;
        }
    ASSERT_GT(n, 1000);
    EXPECT_LT(direct / n, 3.0);
    EXPECT_GT(flipped / n, 100.0);
}

TEST(DemPipeline, DemoHelpNamesTheBundledScene) {
    ScratchDir dir("demo-help");
    const auto r = run_binary(dir, "demo --help");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("scenarios/demo_avakot/scenario.toml"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Kot"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace avalanche
