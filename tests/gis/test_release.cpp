// Release polygons and rasters onto the grid.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numeric>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "avalanche/gis/release.hpp"
#include "geographic_fixture.hpp"
#include "gis_test_support.hpp"

namespace avalanche::gis {
namespace {

using testing::expect_error;
using testing::TempDir;

// The avaKot DEM itself: its own CRS (MGI / Austria Lambert), 5 m cells.
const Dem& avaKot_dem() {
    static const Dem dem = load_dem({testing::avaKot("avaKot_dem.tif")});
    return dem;
}

int released_cells(const Release& r) {
    return static_cast<int>(
        std::count_if(r.thickness.begin(), r.thickness.end(), [](double h) { return h > 0.0; }));
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A GeoJSON polygon in EPSG:31287 coordinates (easting, northing) near the release area.
std::string geojson(const std::string& ring, const std::string& properties = "{}") {
    return R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"EPSG:31287"}},
"features":[{"type":"Feature","id":7,"properties":)" +
           properties + R"(,"geometry":{"type":"Polygon","coordinates":[[)" + ring + "]]}}]}";
}
const std::string kSquare =
    "[177800,376650],[177850,376650],[177850,376700],[177800,376700],[177800,376650]";

TEST(ReleasePolygons, AvaKotReleaseOnTheUtmGridOfTheGeographicDem) {
    TempDir tmp;
    testing::make_geographic_dem(tmp);
    const Dem dem = load_dem({tmp.file("geo.tif")});
    ASSERT_EQ(dem.geo.epsg(), 32632);
    const Release r = rasterize_release_polygons(testing::avaKot("avaKot_release.gpkg"), dem.geo);
    EXPECT_EQ(r.features, 1);
    // About 14,000 m^2 (polygon area) on 900 m^2 cells: 10 to 25 cells.
    EXPECT_GE(released_cells(r), 10);
    EXPECT_LE(released_cells(r), 25);
    EXPECT_EQ(r.feature_cells.at(0), released_cells(r));
    for (std::size_t k = 0; k < r.thickness.size(); ++k) {
        if (r.thickness[k] > 0) {
            EXPECT_DOUBLE_EQ(r.thickness[k], 1.0);  // the `thickness` attribute
            EXPECT_EQ(r.feature_id[k], 1);
        } else {
            EXPECT_EQ(r.feature_id[k], 0);
        }
    }
    EXPECT_NE(r.feature_labels.at(0).find("KoT"), std::string::npos);
    EXPECT_NO_THROW(check_release_on_valid_dem(r, dem));
}

TEST(ReleasePolygons, CellCentreRuleOnTheNativeGrid) {
    const Dem& dem = avaKot_dem();
    const Release r = rasterize_release_polygons(testing::avaKot("avaKot_release.gpkg"), dem.geo);
    // Polygon area / cell area, within the boundary cells' share.
    const double cells = released_cells(r);
    const double area = cells * dem.geo.grid.cell_area();
    EXPECT_GT(area, 10000.0);
    EXPECT_LT(area, 20000.0);
    // The release lies south-west of the DEM centre (release extent y 376625..376833 in a
    // grid spanning 376238..378822): its cells are in the lower (southern) rows.
    int max_j = 0;
    for (std::size_t k = 0; k < r.thickness.size(); ++k)
        if (r.thickness[k] > 0) max_j = std::max(max_j, static_cast<int>(k / dem.geo.grid.nx));
    EXPECT_LT(max_j, dem.geo.grid.ny / 2);
    EXPECT_NEAR(dem.geo.grid.y_center(max_j), 376833.0, 10.0);
}

TEST(ReleasePolygons, ConstantThicknessAndThicknessField) {
    TempDir tmp;
    const GeoGrid& geo = avaKot_dem().geo;
    ReleaseOptions constant;
    constant.thickness = 2.5;
    const Release r =
        rasterize_release_polygons(testing::avaKot("avaKot_release.gpkg"), geo, constant);
    EXPECT_DOUBLE_EQ(*std::max_element(r.thickness.begin(), r.thickness.end()), 2.5);

    write_text(tmp.file("field.geojson"), geojson(kSquare, R"({"depth": 0.8})"));
    ReleaseOptions field;
    field.thickness_field = "depth";
    const Release f = rasterize_release_polygons(tmp.file("field.geojson"), geo, field);
    EXPECT_DOUBLE_EQ(*std::max_element(f.thickness.begin(), f.thickness.end()), 0.8);
    EXPECT_EQ(released_cells(f), 100);  // 50 m x 50 m on 5 m cells, cell centres inside
}

// A GeoPackage as QGIS leaves it after a style was saved in it: the release layer and an
// attribute-only table ('layer_styles'), which holds no polygon and is not read.
TEST(ReleasePolygons, AttributeTablesBesideTheLayerAreSkipped) {
    TempDir tmp;
    const GeoGrid& geo = avaKot_dem().geo;
    const std::string path = tmp.file("styled.gpkg");
    testing::copy_to_geopackage(testing::avaKot("avaKot_release.gpkg"), path, wkbPolygon, true);
    const Release original =
        rasterize_release_polygons(testing::avaKot("avaKot_release.gpkg"), geo);
    const Release styled = rasterize_release_polygons(path, geo);
    EXPECT_EQ(styled.features, 1);
    EXPECT_EQ(styled.thickness, original.thickness);
    ReleaseOptions constant;
    constant.thickness = 2.0;
    EXPECT_EQ(rasterize_release_polygons(path, geo, constant).features, 1);
}

// Curve geometry types (what QGIS writes for a layer of "CurvePolygon" or
// "MultiSurface" type) hold the same polygon: the same cells as the plain polygon.
TEST(ReleasePolygons, CurveGeometryTypesCoverTheCellsOfTheirPolygons) {
    TempDir tmp;
    const GeoGrid& geo = avaKot_dem().geo;
    const Release original =
        rasterize_release_polygons(testing::avaKot("avaKot_release.gpkg"), geo);
    ASSERT_GT(released_cells(original), 100);
    for (const OGRwkbGeometryType type : {wkbCurvePolygon, wkbMultiSurface}) {
        const std::string path = tmp.file(std::string(OGRGeometryTypeToName(type)) + ".gpkg");
        testing::copy_to_geopackage(testing::avaKot("avaKot_release.gpkg"), path, type, false);
        const Release curved = rasterize_release_polygons(path, geo);
        EXPECT_EQ(curved.thickness, original.thickness) << OGRGeometryTypeToName(type);
    }
}

TEST(ReleasePolygons, BadThicknessAttributesAreRefused) {
    TempDir tmp;
    const GeoGrid& geo = avaKot_dem().geo;
    write_text(tmp.file("text.geojson"), geojson(kSquare, R"({"thickness": "deep"})"));
    expect_error<InputError>(
        [&] { rasterize_release_polygons(tmp.file("text.geojson"), geo); },
        {"text.geojson", "feature 7", "'thickness'", "'deep' is not a number"});
    write_text(tmp.file("neg.geojson"), geojson(kSquare, R"({"thickness": -1})"));
    expect_error<InputError>([&] { rasterize_release_polygons(tmp.file("neg.geojson"), geo); },
                             {"neg.geojson", "feature 7", "positive"});
    write_text(tmp.file("none.geojson"), geojson(kSquare, R"({"other": 1})"));
    expect_error<ConfigError>([&] { rasterize_release_polygons(tmp.file("none.geojson"), geo); },
                              {"thickness", "no 'thickness' field"});
    ReleaseOptions missing;
    missing.thickness_field = "depth";
    expect_error<InputError>(
        [&] { rasterize_release_polygons(tmp.file("none.geojson"), geo, missing); },
        {"none.geojson", "no field 'depth'", "other"});
}

TEST(ReleasePolygons, GeometryProblemsAreRefused) {
    TempDir tmp;
    const GeoGrid& geo = avaKot_dem().geo;
    write_text(tmp.file("bowtie.geojson"),
               geojson("[177800,376650],[177850,376700],[177850,376650],[177800,376700],"
                       "[177800,376650]",
                       R"({"thickness": 1})"));
    expect_error<InputError>([&] { rasterize_release_polygons(tmp.file("bowtie.geojson"), geo); },
                             {"bowtie.geojson", "feature 7", "invalid geometry"});

    write_text(tmp.file("far.geojson"),
               geojson("[100000,300000],[100100,300000],[100100,300100],[100000,300000]",
                       R"({"thickness": 1})"));
    expect_error<InputError>([&] { rasterize_release_polygons(tmp.file("far.geojson"), geo); },
                             {"far.geojson", "feature 7", "entirely outside"});

    write_text(tmp.file("tiny.geojson"),
               geojson("[177800.1,376650.1],[177800.2,376650.1],[177800.2,376650.2],"
                       "[177800.1,376650.1]",
                       R"({"thickness": 1})"));
    expect_error<InputError>([&] { rasterize_release_polygons(tmp.file("tiny.geojson"), geo); },
                             {"tiny.geojson", "covers no cell centre"});

    write_text(tmp.file("empty.geojson"), R"({"type":"FeatureCollection","features":[]})");
    expect_error<InputError>([&] { rasterize_release_polygons(tmp.file("empty.geojson"), geo); },
                             {"empty.geojson", "no release polygon"});
}

TEST(ReleasePolygons, ShapefileWithoutShxIsRefusedClearly) {
    TempDir tmp;
    const GeoGrid& geo = avaKot_dem().geo;
    // Convert the GeoPackage to a Shapefile with GDAL, then lose its .shx.
    GDALAllRegister();
    GDALDataset* src =
        GDALDataset::Open(testing::avaKot("avaKot_release.gpkg").c_str(), GDAL_OF_VECTOR);
    ASSERT_NE(src, nullptr);
    GDALDriver* shp = GetGDALDriverManager()->GetDriverByName("ESRI Shapefile");
    GDALDataset* out =
        shp->CreateCopy(tmp.file("rel.shp").c_str(), src, FALSE, nullptr, nullptr, nullptr);
    ASSERT_NE(out, nullptr);
    GDALClose(out);
    GDALClose(src);
    EXPECT_GT(released_cells(rasterize_release_polygons(tmp.file("rel.shp"), geo)), 0);
    std::filesystem::remove(tmp.file("rel.shx"));
    expect_error<InputError>([&] { rasterize_release_polygons(tmp.file("rel.shp"), geo); },
                             {"rel.shp", ".shx", "missing"});
}

TEST(ReleaseRaster, ResampledOntoTheGridAndChecked) {
    TempDir tmp;
    const Dem& dem = avaKot_dem();
    const Release poly =
        rasterize_release_polygons(testing::avaKot("avaKot_release.gpkg"), dem.geo);
    write_geotiff(tmp.file("h.tif"), dem.geo, poly.thickness, BandInfo{"h", "m", -1.0, {}, {}});
    const std::vector<double> h = read_release_raster(tmp.file("h.tif"), dem.geo);
    EXPECT_EQ(h, poly.thickness);  // same grid: the cells come back unchanged

    std::vector<double> negative = poly.thickness;
    negative[5] = -0.5;
    write_geotiff(tmp.file("neg.tif"), dem.geo, negative, BandInfo{"h", "m", -1.0, {}, {}});
    expect_error<InputError>([&] { read_release_raster(tmp.file("neg.tif"), dem.geo); },
                             {"neg.tif", "negative"});
}

TEST(ReleaseOnVoids, ReleaseOnFilledCellsIsRefusedWithTheCount) {
    const Dem& dem = avaKot_dem();
    std::vector<double> h(dem.geo.grid.cells(), 0.0);
    h[0] = 1.0;  // the south-west corner lies outside the avaKot footprint
    ASSERT_NE(dem.filled_mask[0], 0);
    expect_error<InputError>([&] { check_release_on_valid_dem(h, dem); }, {"1 release cells"});
}

}  // namespace
}  // namespace avalanche::gis
