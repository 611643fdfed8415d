// Precedence defaults < scenario file < flags, and which name an error carries.
#include <gtest/gtest.h>

#include "avalanche/app/scenario_overrides.hpp"
#include "avalanche/core/error.hpp"
#include "cli_test_support.hpp"

namespace avalanche {
namespace {

template <class F>
std::string config_error(F f) {
    try {
        f();
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

TEST(ScenarioOverrides, FlagsWinOverTheFileAndUnsetFlagsKeepIt) {
    test::ScratchDir dir("precedence");
    const std::string file = dir.write("scenario.toml", test::kSmallChute);
    ScenarioOverrides o;
    o.cfl = 0.45;
    o.delta = 15.0;
    o.cell_size = 0.25;
    const Scenario s = assemble_scenario(file, o);
    EXPECT_EQ(s.numerics.cfl, 0.45);
    EXPECT_EQ(s.material.delta_deg, 15.0);
    EXPECT_EQ(s.cell_size, 0.25);
    EXPECT_EQ(s.material.phi_deg, 35.0);                      // file
    EXPECT_EQ(s.numerics.t_end, 0.5);                         // file
    EXPECT_EQ(s.numerics.limiter, NumericsParams{}.limiter);  // default
}

TEST(ScenarioOverrides, ErrorsNameTheFlagWhenAFlagSetTheValue) {
    test::ScratchDir dir("naming");
    const std::string file = dir.write("scenario.toml", test::kSmallChute);
    ScenarioOverrides o;
    o.cell_size = 0.3;  // does not divide 10 m x 4 m
    auto m = config_error([&] { assemble_scenario(file, o); });
    EXPECT_EQ(m.rfind("--cell-size: expected a cell size that divides", 0), 0u) << m;
    // delta > phi where only phi came from a flag: the key is delta_deg, from the file.
    o = {};
    o.phi = 15.0;
    m = config_error([&] { assemble_scenario(file, o); });
    EXPECT_EQ(m.rfind(file + ": material.delta_deg:", 0), 0u) << m;
    o = {};
    o.stop_ke_fraction = 1.5;
    m = config_error([&] { assemble_scenario(file, o); });
    EXPECT_EQ(m.rfind("--stop-ke-fraction: expected a fraction in [0, 1)", 0), 0u) << m;
}

TEST(ScenarioOverrides, FlagsThatDoNotFitTheScenarioAreRefused) {
    Scenario s;  // chute with a cap
    ScenarioOverrides o;
    o.thickness = 1.0;
    EXPECT_EQ(config_error([&] { apply_overrides(s, o); }).rfind("--thickness: a cap release", 0),
              0u);
    o = {};
    o.volume = 10.0;
    EXPECT_EQ(
        config_error([&] { apply_overrides(s, o); }).rfind("--volume: applies to a polygon", 0),
        0u);
    o = {};
    o.crs = "EPSG:2056";
    EXPECT_EQ(config_error([&] { apply_overrides(s, o); }).rfind("--crs: applies to a DEM", 0), 0u);
    o = {};
    o.earth_pressure = "rankine";
    EXPECT_EQ(
        config_error([&] { apply_overrides(s, o); }).rfind("--earth-pressure: expected one of", 0),
        0u);
}

TEST(ScenarioOverrides, DemAndReleaseFlagsMakeADemScenario) {
    ScenarioOverrides o;
    o.dem = {"a.tif", "b.tif"};
    o.release = "thickness.TIF";
    o.crs = "EPSG:32633";
    Scenario s = assemble_scenario(std::nullopt, o);
    EXPECT_EQ(std::get<DemTerrainSpec>(s.terrain).dem_paths, o.dem);
    EXPECT_EQ(std::get<DemTerrainSpec>(s.terrain).crs, "EPSG:32633");
    EXPECT_EQ(std::get<RasterReleaseSpec>(s.release).path, "thickness.TIF");

    o.release = "release.gpkg";
    o.crs.reset();
    o.thickness_field = "d";
    o.volume = 5e4;
    o.points = "points.csv";
    s = assemble_scenario(std::nullopt, o);
    const auto& p = std::get<PolygonReleaseSpec>(s.release);
    EXPECT_EQ(p.path, "release.gpkg");
    EXPECT_EQ(p.thickness, std::nullopt);
    EXPECT_EQ(p.thickness_field, "d");
    EXPECT_EQ(p.volume, 5e4);
    ASSERT_TRUE(s.points.has_value());
    EXPECT_EQ(s.points->path, "points.csv");

    o.volume = -1.0;
    EXPECT_EQ(config_error([&] { assemble_scenario(std::nullopt, o); }).rfind("--volume:", 0), 0u);
    ScenarioOverrides no_release;
    no_release.dem = {"a.tif"};
    EXPECT_EQ(
        config_error([&] { assemble_scenario(std::nullopt, no_release); }).rfind("--release:", 0),
        0u);
}

// A polygon release's thickness comes from a number or from a field: the flag for one
// replaces the file's other, as any flag its key; both at once are refused up front, not
// once the DEM is read.
TEST(ScenarioOverrides, AThicknessFlagReplacesTheFilesThicknessFieldAndTheReverse) {
    test::ScratchDir dir("thickness");
    const std::string dem = "[terrain]\ntype = \"dem\"\ndem = \"a.tif\"\n";
    const std::string by_field = dir.write(
        "field.toml", dem + "[release]\npolygons = \"r.gpkg\"\nthickness_field = \"d\"\n");
    const std::string by_number =
        dir.write("number.toml", dem + "[release]\npolygons = \"r.gpkg\"\nthickness = 1.5\n");
    ScenarioOverrides o;
    o.thickness = 2.0;
    Scenario s = assemble_scenario(by_field, o);
    EXPECT_EQ(std::get<PolygonReleaseSpec>(s.release).thickness, 2.0);
    EXPECT_EQ(std::get<PolygonReleaseSpec>(s.release).thickness_field, "");
    o = {};
    o.thickness_field = "depth";
    s = assemble_scenario(by_number, o);
    EXPECT_EQ(std::get<PolygonReleaseSpec>(s.release).thickness, std::nullopt);
    EXPECT_EQ(std::get<PolygonReleaseSpec>(s.release).thickness_field, "depth");

    o.thickness = 2.0;
    const std::string both_flags = config_error([&] { assemble_scenario(by_number, o); });
    EXPECT_EQ(both_flags.rfind("--thickness: give either --thickness or --thickness-field", 0), 0u)
        << both_flags;
    const std::string both_keys = dir.write(
        "both.toml",
        dem + "[release]\npolygons = \"r.gpkg\"\nthickness = 1.5\nthickness_field = \"d\"\n");
    const std::string in_file = config_error([&] { assemble_scenario(both_keys, {}); });
    EXPECT_EQ(in_file.rfind(both_keys + ": release.thickness: give either", 0), 0u) << in_file;
}

// Inputs that a scene cannot use are refused before anything is read, naming the file
// and its key: monitoring points on the chute (whose frame has no CRS to place them
// in), an analytic release shape on a DEM.
TEST(ScenarioOverrides, PointsOnTheChuteAndShapesOnADemAreRefusedUpFront) {
    test::ScratchDir dir("misfits");
    const std::string chute =
        dir.write("chute.toml", std::string(test::kSmallChute) + "\n[points]\nfile = \"p.csv\"\n");
    const std::string points = config_error([&] { assemble_scenario(chute, {}); });
    EXPECT_EQ(points.rfind(chute + ": points.file: monitoring points need a DEM terrain", 0), 0u)
        << points;
    ScenarioOverrides o;
    o.points = "p.csv";
    const std::string flag =
        config_error([&] { assemble_scenario(dir.write("plain.toml", test::kSmallChute), o); });
    EXPECT_EQ(flag.rfind("--points: monitoring points need a DEM terrain", 0), 0u) << flag;

    const std::string dem_shape =
        dir.write("dem_shape.toml",
                  "[terrain]\ntype = \"dem\"\ndem = \"a.tif\"\n[release]\nshape = \"cap\"\n"
                  "center = [1.0, 1.0]\nradius = 1.0\n");
    const std::string shape = config_error([&] { assemble_scenario(dem_shape, {}); });
    EXPECT_EQ(shape.rfind(dem_shape + ": release.shape: a DEM terrain takes release polygons", 0),
              0u)
        << shape;
}

// A grid CRS that PROJ cannot read, or one not in metres, is refused with the scenario,
// naming the flag or the file's key, before a DEM is read or a folder made.
TEST(ScenarioOverrides, TheGridCrsIsCheckedWithTheScenario) {
    ScenarioOverrides o;
    o.dem = {"a.tif"};
    o.release = "r.gpkg";
    o.crs = "EPSG:999999";
    const std::string unknown = config_error([&] { assemble_scenario(std::nullopt, o); });
    EXPECT_EQ(unknown.rfind("--crs: cannot interpret 'EPSG:999999'", 0), 0u) << unknown;
    o.crs = "EPSG:4326";
    const std::string degrees = config_error([&] { assemble_scenario(std::nullopt, o); });
    EXPECT_EQ(degrees.rfind("--crs: the requested CRS", 0), 0u) << degrees;
    EXPECT_NE(degrees.find("not a projected CRS"), std::string::npos) << degrees;
    o.crs = "EPSG:32633";
    EXPECT_NO_THROW(assemble_scenario(std::nullopt, o));

    test::ScratchDir dir("crs");
    const std::string file =
        dir.write("scenario.toml",
                  "[terrain]\ntype = \"dem\"\ndem = \"a.tif\"\ncrs = \"EPSG:4326\"\n"
                  "[release]\npolygons = \"r.gpkg\"\nthickness = 1.0\n");
    const std::string in_file = config_error([&] { assemble_scenario(file, {}); });
    EXPECT_EQ(in_file.rfind(file + ": terrain.crs: the requested CRS", 0), 0u) << in_file;
}

TEST(ScenarioOverrides, TextNamesTheFlagsAsACommandLineGivesThem) {
    EXPECT_EQ(overrides_text(ScenarioOverrides{}), "");
    ScenarioOverrides o;
    o.dem = {"a.tif", "my tiles/b.tif"};
    o.release = "it's.gpkg";
    o.thickness = 1.5;
    o.delta = 25.0;
    o.cfl = 0.1;
    o.quality = "draft";
    o.rest_faces = false;
    // In --help's order; a value a shell would split or unquote in single quotes.
    EXPECT_EQ(overrides_text(o),
              "--dem a.tif --dem 'my tiles/b.tif' --release 'it'\\''s.gpkg' --thickness 1.5 "
              "--delta 25 --cfl 0.1 --no-rest-faces --quality draft");
    o = {};
    o.rest_faces = true;
    o.crs = "EPSG:32633";
    EXPECT_EQ(overrides_text(o), "--crs EPSG:32633 --rest-faces");
}

}  // namespace
}  // namespace avalanche
