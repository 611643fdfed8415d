// Monitoring points from CSV and OGR layers.
#include <gtest/gtest.h>

#include <fstream>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/points.hpp"
#include "gis_test_support.hpp"

namespace avalanche::gis {
namespace {

using testing::expect_error;
using testing::TempDir;

// A 100 x 80 grid of 10 m cells in UTM 32N.
GeoGrid utm_grid() {
    return GeoGrid{Grid{100, 80, 10.0, 10.0, 600000.0, 5200000.0}, utm_crs_wkt_for(9.0, 47.0)};
}

TEST(Points, CsvInTheGridCrs) {
    TempDir tmp;
    std::ofstream(tmp.file("p.csv")) << "# monitoring points\nname, x, y, note\n"
                                     << "top,600005,5200795,north-west corner cell\n"
                                     << "\"fan\",600995.5,5200000.1,south-east\n";
    const auto p = read_points(tmp.file("p.csv"), "", utm_grid());
    ASSERT_EQ(p.size(), 2u);
    EXPECT_EQ(p[0].name, "top");
    EXPECT_EQ(p[0].i, 0);
    EXPECT_EQ(p[0].j, 79);  // the northern row
    EXPECT_EQ(p[1].name, "fan");
    EXPECT_EQ(p[1].i, 99);
    EXPECT_EQ(p[1].j, 0);
}

// "CSV UTF-8" as spreadsheets save it starts with a byte-order mark; the header is read
// past it.
TEST(Points, CsvWithAByteOrderMark) {
    const auto p = parse_points_csv("\xEF\xBB\xBFname,x,y\nfan,600995.5,5200000.1\n", "bom.csv");
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].name, "fan");
    EXPECT_EQ(p[0].x, 600995.5);
}

// Points in a GeoPackage that also holds an attribute-only table (QGIS's saved styles).
TEST(Points, GeoPackageWithAnAttributeTable) {
    TempDir tmp;
    const GeoGrid geo{
        // the avaKot grid, as in GeoPackageFromAvaKot
        Grid{439, 517, 4.997688906601, 4.997688906601, 176973.437998359208, 376237.836376162944},
        "EPSG:31287"};
    testing::copy_to_geopackage(testing::avaKot("avaKot_points.gpkg"), tmp.file("styled.gpkg"),
                                wkbPoint, true);
    const auto original = read_points(testing::avaKot("avaKot_points.gpkg"), "", geo);
    const auto styled = read_points(tmp.file("styled.gpkg"), "", geo);
    ASSERT_EQ(styled.size(), original.size());
    ASSERT_FALSE(styled.empty());
    for (std::size_t k = 0; k < styled.size(); ++k) {
        EXPECT_EQ(styled[k].name, original[k].name);
        EXPECT_EQ(styled[k].i, original[k].i);
        EXPECT_EQ(styled[k].j, original[k].j);
    }
}

TEST(Points, CsvInAnotherCrsIsReprojected) {
    TempDir tmp;
    const GeoGrid geo = utm_grid();
    // The grid centre (600500, 5200400) in UTM 32N is 10.3206878 E, 46.9495113 N
    // (gdaltransform).
    std::ofstream(tmp.file("p.csv")) << "name,x,y\ncentre,10.3206878,46.9495113\n";
    const auto p = read_points(tmp.file("p.csv"), "EPSG:4326", geo);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_NEAR(p[0].x, 600500.0, 0.05);
    EXPECT_NEAR(p[0].y, 5200400.0, 0.05);
}

TEST(Points, GeoPackageFromAvaKot) {
    // The avaKot grid (EPSG:31287 extent) is enough: reuse its numbers without the DEM.
    const GeoGrid geo{
        Grid{439, 517, 4.997688906601, 4.997688906601, 176973.437998359208, 376237.836376162944},
        "EPSG:31287"};
    const auto p = read_points(testing::avaKot("avaKot_points.gpkg"), "", geo);
    ASSERT_EQ(p.size(), 1u);
    EXPECT_EQ(p[0].name, "point_1");  // the `id` field is empty: named after the FID
    EXPECT_NEAR(p[0].x, 178342.713179185, 1e-6);
    EXPECT_NEAR(p[0].y, 377698.857655861, 1e-6);
    EXPECT_EQ(p[0].i, static_cast<int>((178342.713179185 - geo.grid.x0) / geo.grid.dx));
    EXPECT_EQ(p[0].j, static_cast<int>((377698.857655861 - geo.grid.y0) / geo.grid.dy));
}

TEST(Points, ProblemsNameTheLineOrPoint) {
    TempDir tmp;
    const GeoGrid geo = utm_grid();
    std::ofstream(tmp.file("out.csv")) << "name,x,y\na,600100,5200100\nfar,700000,5200100\n";
    expect_error<InputError>([&] { read_points(tmp.file("out.csv"), "", geo); },
                             {"out.csv", "line 3", "'far'", "outside the grid"});
    std::ofstream(tmp.file("bad.csv")) << "name,x,y\na,600100,5200100\nb,600100\n";
    expect_error<InputError>([&] { read_points(tmp.file("bad.csv"), "", geo); },
                             {"bad.csv", "line 3", "2 columns"});
    std::ofstream(tmp.file("nan.csv")) << "name,x,y\na,600100,north\n";
    expect_error<InputError>([&] { read_points(tmp.file("nan.csv"), "", geo); },
                             {"nan.csv", "line 2", "numbers"});
    std::ofstream(tmp.file("dup.csv")) << "name,x,y\na,600100,5200100\na,600200,5200100\n";
    expect_error<InputError>([&] { read_points(tmp.file("dup.csv"), "", geo); },
                             {"dup.csv", "line 3", "duplicate", "'a'"});
    std::ofstream(tmp.file("head.csv")) << "id;east;north\n";
    expect_error<InputError>([&] { read_points(tmp.file("head.csv"), "", geo); },
                             {"head.csv", "line 1", "name,x,y"});
    expect_error<ConfigError>([&] { read_points(tmp.file("dup.csv"), "EPSG:bogus", geo); },
                              {"points_crs"});
}

// Each name becomes a group of monitoring.h5: names HDF5 cannot take are refused when the
// points are read, not after the run; commas and quotes are fine (monitoring.csv quotes
// them).
TEST(Points, NamesThatCannotNameAnHdf5GroupAreRefusedWhenRead) {
    TempDir tmp;
    const GeoGrid geo = utm_grid();
    std::ofstream(tmp.file("slash.csv")) << "name,x,y\na,600100,5200100\nLift A/B,600200,5200100\n";
    expect_error<InputError>([&] { read_points(tmp.file("slash.csv"), "", geo); },
                             {"slash.csv", "line 3", "'Lift A/B'", "without '/'"});
    std::ofstream(tmp.file("dot.csv")) << "name,x,y\n.,600100,5200100\n";
    expect_error<InputError>([&] { read_points(tmp.file("dot.csv"), "", geo); },
                             {"dot.csv", "line 2", "'.'", "other than '.'"});
    std::ofstream(tmp.file("p.geojson")) << R"({"type": "FeatureCollection",
               "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},
               "features": [
                 {"type": "Feature", "properties": {"name": "Haus Moser, Nord"},
                  "geometry": {"type": "Point", "coordinates": [600100, 5200100]}},
                 {"type": "Feature", "properties": {"name": "Rinne \"Ost\""},
                  "geometry": {"type": "Point", "coordinates": [600200, 5200100]}},
                 {"type": "Feature", "properties": {"name": ".."},
                  "geometry": {"type": "Point", "coordinates": [600300, 5200100]}}]})";
    const auto p = read_points(tmp.file("p.geojson"), "", geo);
    ASSERT_EQ(p.size(), 3u);
    EXPECT_EQ(p[0].name, "Haus Moser, Nord");
    EXPECT_EQ(p[1].name, "Rinne \"Ost\"");
    EXPECT_EQ(p[2].name, "..");  // a group name like any other in HDF5
    std::ofstream(tmp.file("slash.geojson")) << R"({"type": "FeatureCollection",
               "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},
               "features": [
                 {"type": "Feature", "properties": {"name": "Lift A/B"},
                  "geometry": {"type": "Point", "coordinates": [600100, 5200100]}}]})";
    expect_error<InputError>([&] { read_points(tmp.file("slash.geojson"), "", geo); },
                             {"slash.geojson", "feature 0", "'Lift A/B'", "monitoring.h5"});
}

}  // namespace
}  // namespace avalanche::gis
