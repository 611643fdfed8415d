// Scenario files: every key is read into the typed Scenario, and every refusal names
// the file and the key.
#include <gtest/gtest.h>

#include "avalanche/core/error.hpp"
#include "avalanche/io/scenario_file.hpp"
#include "io_test_support.hpp"

namespace avalanche {
namespace {

const char* kFullChute = R"(
[terrain]
type = "chute"
slope_deg = 40.0
length = 50.0
width = 30
transition = [20.0, 26.0]
runout_slope_deg = 5.0

[release]
shape = "paraboloid"
center = [6.0, 15.0]
radius = 3.0
thickness = 1.5

[material]
phi_deg = 33.0
delta_deg = 21.0
earth_pressure = "isotropic"
density = 1800.0

[numerics]
cell_size = 0.5
scheme = "godunov"
cfl = 0.3
t_end = 12.5
output_interval = 0.5
limiter = "superbee"
h_min = 1e-4
boundary = "wall"
source_substeps = 3
stop_ke_fraction = 1e-3
stop_duration = 2.0
splitting = "sls"
gravity = 9.80665
rest_faces = true

[points]
file = "points.csv"
crs = "EPSG:2056"

[output]
h_threshold = 0.05
pressure_high_kpa = 40.0
pressure_low_kpa = 4.0
)";

Scenario parse(const std::string& text, const std::string& base = "") {
    return parse_scenario_text(text, "scenario.toml", base);
}

// The message of the ConfigError thrown by f(), or "" if none.
template <class F>
std::string config_error(F f) {
    try {
        f();
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.code(), ExitCode::usage);
        return e.what();
    }
    return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return text.replace(pos, from.size(), to);
}

TEST(ScenarioFile, ReadsEveryKeyOfAChuteScenario) {
    const Scenario s = parse(kFullChute, "/data/case");
    // Every key is valid but the points, which a chute cannot place (no CRS): read here,
    // refused by validate (ScenarioOverrides.PointsOnTheChuteAndShapesOnADemAreRefusedUpFront).
    Scenario without_points = s;
    without_points.points.reset();
    validate(without_points);
    EXPECT_THROW(validate(s), ConfigError);
    const auto& c = std::get<ChuteGeometry>(s.terrain);
    EXPECT_EQ(c.slope_deg, 40.0);
    EXPECT_EQ(c.length, 50.0);
    EXPECT_EQ(c.width, 30.0);  // an integer is a number too
    EXPECT_EQ(c.transition_start, 20.0);
    EXPECT_EQ(c.transition_end, 26.0);
    EXPECT_EQ(c.runout_slope_deg, 5.0);
    const auto& p = std::get<ParaboloidRelease>(std::get<ReleaseShape>(s.release));
    EXPECT_EQ(p.center, (std::array<double, 2>{6.0, 15.0}));
    EXPECT_EQ(p.radius, 3.0);
    EXPECT_EQ(p.thickness, 1.5);
    EXPECT_EQ(s.material.phi_deg, 33.0);
    EXPECT_EQ(s.material.delta_deg, 21.0);
    EXPECT_EQ(s.material.earth_pressure, EarthPressureModel::isotropic);
    EXPECT_EQ(s.material.density, 1800.0);
    EXPECT_EQ(s.cell_size, 0.5);
    EXPECT_EQ(s.numerics.scheme, Scheme::godunov);
    EXPECT_EQ(s.numerics.cfl, 0.3);
    EXPECT_EQ(s.numerics.t_end, 12.5);
    EXPECT_EQ(s.numerics.output_interval, 0.5);
    EXPECT_EQ(s.numerics.limiter, Limiter::superbee);
    EXPECT_EQ(s.numerics.h_min, 1e-4);
    EXPECT_EQ(s.numerics.boundary, Boundary::wall);
    EXPECT_EQ(s.numerics.source_substeps, 3);
    EXPECT_EQ(s.numerics.stop_ke_fraction, 1e-3);
    EXPECT_EQ(s.numerics.stop_duration, 2.0);
    EXPECT_EQ(s.numerics.splitting, Splitting::sls);
    EXPECT_EQ(s.numerics.gravity, 9.80665);
    EXPECT_TRUE(s.numerics.rest_faces);
    ASSERT_TRUE(s.points.has_value());
    EXPECT_EQ(s.points->path, "/data/case/points.csv");  // relative to the scenario's folder
    EXPECT_EQ(s.points->crs, "EPSG:2056");
    EXPECT_EQ(s.output.h_threshold, 0.05);
    EXPECT_EQ(s.output.pressure_high_kpa, 40.0);
    EXPECT_EQ(s.output.pressure_low_kpa, 4.0);
    EXPECT_EQ(s.source, "scenario.toml");
}

TEST(ScenarioFile, OptionalTablesKeepTheirDefaults) {
    const Scenario s = parse(R"(
[terrain]
type = "chute"
[release]
shape = "cap"
center = [7.5, 20.0]
radius = 2.5
[numerics]
cell_size = 1.0
)");
    const NumericsParams n;
    const MaterialParams m;
    EXPECT_EQ(s.numerics.cfl, n.cfl);
    EXPECT_EQ(s.numerics.limiter, n.limiter);
    EXPECT_EQ(s.material.phi_deg, m.phi_deg);
    EXPECT_FALSE(std::get<ChuteGeometry>(s.terrain).has_transition());
    EXPECT_FALSE(s.points.has_value());
    EXPECT_EQ(s.output.h_threshold, OutputParams{}.h_threshold);
    const auto& cap = std::get<CapRelease>(std::get<ReleaseShape>(s.release));
    EXPECT_EQ(cap.radius, 2.5);
}

TEST(ScenarioFile, ReadsBoxReleases) {
    const Scenario s = parse(R"(
[terrain]
type = "chute"
[release]
shape = "box"
x = [1.0, 3.0]
y = [0.5, 1.5]
thickness = 0.4
)");
    const auto& b = std::get<BoxRelease>(std::get<ReleaseShape>(s.release));
    EXPECT_EQ(b.x, (std::array<double, 2>{1.0, 3.0}));
    EXPECT_EQ(b.y, (std::array<double, 2>{0.5, 1.5}));
    EXPECT_EQ(b.thickness, 0.4);
}

TEST(ScenarioFile, ReadsDemScenariosWithPathsRelativeToTheFile) {
    const Scenario s = parse(R"(
[terrain]
type = "dem"
dem = ["a.tif", "/abs/b.tif"]
crs = "EPSG:32633"
[release]
polygons = "release.gpkg"
thickness_field = "thick"
volume = 1e5
)",
                             "/data/case");
    validate(s);
    const auto& d = std::get<DemTerrainSpec>(s.terrain);
    EXPECT_EQ(d.dem_paths, (std::vector<std::string>{"/data/case/a.tif", "/abs/b.tif"}));
    EXPECT_EQ(d.crs, "EPSG:32633");
    const auto& p = std::get<PolygonReleaseSpec>(s.release);
    EXPECT_EQ(p.path, "/data/case/release.gpkg");
    EXPECT_EQ(p.thickness, std::nullopt);  // thickness and thickness_field exclude each other
    EXPECT_EQ(p.thickness_field, "thick");
    EXPECT_EQ(p.volume, 1e5);
    EXPECT_EQ(s.cell_size, 0.0);  // automatic

    const Scenario r = parse(R"(
[terrain]
type = "dem"
dem = "area.tif"
[release]
raster = "thickness.tif"
)",
                             "case");
    EXPECT_EQ(std::get<DemTerrainSpec>(r.terrain).dem_paths,
              (std::vector<std::string>{"case/area.tif"}));
    EXPECT_EQ(std::get<RasterReleaseSpec>(r.release).path, "case/thickness.tif");
}

TEST(ScenarioFile, RefusesUnknownTablesAndKeys) {
    const auto extra =
        config_error([] { parse(std::string(kFullChute) + "\n[extras]\nfoo = 1\n"); });
    EXPECT_NE(extra.find("scenario.toml: extras"), std::string::npos) << extra;
    const auto m =
        config_error([] { parse(replaced(kFullChute, "cfl = 0.3", "cfl = 0.3\ncfll = 0.2")); });
    EXPECT_NE(m.find("scenario.toml: numerics.cfll: unknown key"), std::string::npos) << m;
    // A key of another shape: a cap has no thickness.
    const auto cap = config_error(
        [] { parse(replaced(kFullChute, "shape = \"paraboloid\"", "shape = \"cap\"")); });
    EXPECT_NE(cap.find("release.thickness: unknown key"), std::string::npos) << cap;
    // A DEM key in a chute.
    const auto dem = config_error(
        [] { parse(replaced(kFullChute, "runout_slope_deg = 5.0", "dem = \"a.tif\"")); });
    EXPECT_NE(dem.find("terrain.dem: unknown key"), std::string::npos) << dem;
}

TEST(ScenarioFile, RefusesWrongTypesNamingTheKey) {
    auto m = config_error([] { parse(replaced(kFullChute, "cfl = 0.3", "cfl = \"0.3\"")); });
    EXPECT_EQ(m, "scenario.toml: numerics.cfl: expected a number, got a string");
    m = config_error([] { parse(replaced(kFullChute, "scheme = \"godunov\"", "scheme = 2")); });
    EXPECT_EQ(m, "scenario.toml: numerics.scheme: expected a string, got an integer");
    m = config_error(
        [] { parse(replaced(kFullChute, "source_substeps = 3", "source_substeps = 2.5")); });
    EXPECT_NE(m.find("numerics.source_substeps: expected an integer"), std::string::npos) << m;
    m = config_error([] { parse(replaced(kFullChute, "rest_faces = true", "rest_faces = 1")); });
    EXPECT_EQ(m, "scenario.toml: numerics.rest_faces: expected true or false, got an integer");
    m = config_error(
        [] { parse(replaced(kFullChute, "transition = [20.0, 26.0]", "transition = 20.0")); });
    EXPECT_NE(m.find("terrain.transition: expected an array of two numbers"), std::string::npos)
        << m;
    m = config_error([] {
        parse(
            "material = 3\n[terrain]\ntype = \"chute\"\n[release]\nshape = \"cap\"\n"
            "center = [1.0, 1.0]\nradius = 1.0\n");
    });
    EXPECT_EQ(m, "scenario.toml: material: expected a table [material], got an integer");
}

TEST(ScenarioFile, RefusesBadChoices) {
    auto m = config_error(
        [] { parse(replaced(kFullChute, "scheme = \"godunov\"", "scheme = \"muscl\"")); });
    EXPECT_EQ(
        m, "scenario.toml: numerics.scheme: expected one of \"waf\", \"godunov\", got \"muscl\"");
    m = config_error([] { parse(replaced(kFullChute, "\"isotropic\"", "\"coulomb\"")); });
    EXPECT_NE(m.find("material.earth_pressure: expected one of"), std::string::npos) << m;
    m = config_error([] { parse(replaced(kFullChute, "type = \"chute\"", "type = \"plane\"")); });
    EXPECT_NE(m.find("terrain.type: expected \"chute\" or \"dem\""), std::string::npos) << m;
    m = config_error([] { parse(replaced(kFullChute, "\"paraboloid\"", "\"cone\"")); });
    EXPECT_NE(m.find("release.shape: expected one of"), std::string::npos) << m;
}

TEST(ScenarioFile, RefusesMissingTablesAndKeys) {
    auto m = config_error([] { parse("[release]\nshape = \"cap\"\n"); });
    EXPECT_NE(m.find("terrain.type: missing"), std::string::npos) << m;
    m = config_error([] { parse(replaced(kFullChute, "radius = 3.0\n", "")); });
    EXPECT_NE(m.find("release.radius: missing"), std::string::npos) << m;
}

// Range checks come from the core validators, with the file named in front.
TEST(ScenarioFile, LoadScenarioRefusesOutOfRangeValuesNamingFileAndKey) {
    test::ScratchDir dir("ranges");
    const auto load_with = [&](const std::string& from, const std::string& to) {
        const std::string path = dir.write("scenario.toml", replaced(kFullChute, from, to));
        return config_error([&] { load_scenario(path); });
    };
    const std::string file = dir.file("scenario.toml") + ": ";
    auto m = load_with("cfl = 0.3", "cfl = 0.6");
    EXPECT_EQ(m.rfind(file + "numerics.cfl: expected a Courant number in (0, 0.5]", 0), 0u) << m;
    m = load_with("t_end = 12.5", "t_end = 0.0");
    EXPECT_EQ(m.rfind(file + "numerics.t_end:", 0), 0u) << m;
    m = load_with("t_end = 12.5", "t_end = -1.0");
    EXPECT_EQ(m.rfind(file + "numerics.t_end:", 0), 0u) << m;
    m = load_with("delta_deg = 21.0\nearth_pressure = \"isotropic\"", "delta_deg = 40.0");
    EXPECT_EQ(m.rfind(file + "material.delta_deg:", 0), 0u) << m;
    EXPECT_NE(m.find("exceeds the internal friction angle"), std::string::npos) << m;
    m = load_with("cell_size = 0.5", "cell_size = 0.7");  // does not divide 50 x 30 m
    EXPECT_EQ(m.rfind(file + "numerics.cell_size:", 0), 0u) << m;
    m = load_with("pressure_low_kpa = 4.0", "pressure_low_kpa = 50.0");
    EXPECT_EQ(m.rfind(file + "output.pressure_high_kpa:", 0), 0u) << m;
}

TEST(ScenarioFile, UnreadableOrInvalidTomlIsAnInputError) {
    try {
        load_scenario("/nonexistent/scenario.toml");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_EQ(e.code(), ExitCode::input);
        EXPECT_NE(std::string(e.what()).find("/nonexistent/scenario.toml"), std::string::npos);
    }
    try {
        parse("[terrain\ntype = \"chute\"\n");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("scenario.toml: line 1"), std::string::npos)
            << e.what();
    }
}

TEST(ScenarioFile, ChuteRefusesPolygonReleases) {
    const Scenario s = parse(R"(
[terrain]
type = "chute"
[release]
polygons = "r.gpkg"
thickness = 1.0
[numerics]
cell_size = 1.0
)");
    const auto m = config_error([&] { validate_with_source(s); });
    EXPECT_EQ(m.rfind("scenario.toml: release.polygons:", 0), 0u) << m;
}

}  // namespace
}  // namespace avalanche
