// COG GeoTIFFs, QGIS styles and PNG quick-looks.
#include <cpl_minixml.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <iterator>
#include <fstream>
#include <limits>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/quicklook.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "avalanche/gis/style.hpp"
#include "gis_test_support.hpp"

namespace avalanche::gis {
namespace {

using testing::expect_error;
using testing::TempDir;

GeoGrid utm_grid(int nx, int ny) {
    return GeoGrid{Grid{nx, ny, 5.0, 5.0, 600000.0, 5200000.0}, utm_crs_wkt_for(9.0, 47.0)};
}

TEST(WriteGeotiff, CogWithCrsNodataUnitsAndDescription) {
    TempDir tmp;
    const GeoGrid geo = utm_grid(600, 520);  // large enough for overviews
    std::vector<double> depth(geo.grid.cells(), -9999.0);
    for (std::size_t k = 0; k < depth.size(); k += 3)
        depth[k] = 0.001 * static_cast<double>(k % 997);
    BandInfo band{"maximum flow depth (bed-normal)", "m", -9999.0, {{"THICKNESS", "bed-normal"}}, {}};
    write_geotiff(tmp.file("max_depth.tif"), geo, depth, band);

    GDALAllRegister();
    GDALDataset* ds = GDALDataset::Open(tmp.file("max_depth.tif").c_str(), GDAL_OF_RASTER);
    ASSERT_NE(ds, nullptr);
    EXPECT_STREQ(ds->GetMetadataItem("LAYOUT", "IMAGE_STRUCTURE"), "COG");
    EXPECT_STREQ(ds->GetMetadataItem("COMPRESSION", "IMAGE_STRUCTURE"), "DEFLATE");
    OGRSpatialReference srs(*ds->GetSpatialRef());
    srs.AutoIdentifyEPSG();
    EXPECT_STREQ(srs.GetAuthorityCode(nullptr), "32632");
    double gt[6];
    ds->GetGeoTransform(gt);
    EXPECT_DOUBLE_EQ(gt[0], 600000.0);
    EXPECT_DOUBLE_EQ(gt[3], 5200000.0 + 520 * 5.0);
    EXPECT_DOUBLE_EQ(gt[5], -5.0);
    GDALRasterBand* b = ds->GetRasterBand(1);
    EXPECT_EQ(b->GetRasterDataType(), GDT_Float32);
    int has_nodata = 0;
    EXPECT_DOUBLE_EQ(b->GetNoDataValue(&has_nodata), -9999.0);
    EXPECT_TRUE(has_nodata);
    EXPECT_STREQ(b->GetDescription(), "maximum flow depth (bed-normal)");
    EXPECT_STREQ(b->GetUnitType(), "m");
    EXPECT_STREQ(b->GetMetadataItem("THICKNESS"), "bed-normal");
    EXPECT_GT(b->GetOverviewCount(), 0);
    GDALClose(ds);
    EXPECT_FALSE(std::filesystem::exists(tmp.file("max_depth.tif.part")));
    EXPECT_FALSE(std::filesystem::exists(tmp.file("max_depth.tif.aux.xml")));
}

// The predictor is a choice of compression only: with and without it the same values
// read back, and the file says which it used.
TEST(WriteGeotiff, PredictorAsAskedSameValues) {
    TempDir tmp;
    const GeoGrid geo = utm_grid(300, 200);
    std::vector<double> values(geo.grid.cells(), -9999.0);
    for (std::size_t k = 0; k < values.size(); k += 7) values[k] = 1000.0 + 0.37 * static_cast<double>(k % 1013);
    const BandInfo band{"elevation", "m", -9999.0, {}, {}};
    write_geotiff(tmp.file("with.tif"), geo, values, band);
    write_geotiff(tmp.file("without.tif"), geo, values, band, SampleType::float32, Predictor::none);
    GDALAllRegister();
    std::vector<std::vector<float>> read;
    for (const char* name : {"with.tif", "without.tif"}) {
        GDALDataset* ds = GDALDataset::Open(tmp.file(name).c_str(), GDAL_OF_RASTER);
        ASSERT_NE(ds, nullptr) << name;
        const char* p = ds->GetMetadataItem("PREDICTOR", "IMAGE_STRUCTURE");
        if (std::string(name) == "with.tif") {
            ASSERT_NE(p, nullptr);
            EXPECT_STREQ(p, "3") << "the floating-point predictor";
        } else {
            EXPECT_EQ(p, nullptr) << "no predictor";
        }
        std::vector<float> v(geo.grid.cells());
        ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 300, 200, v.data(), 300, 200, GDT_Float32, 0, 0,
                                                 nullptr),
                  CE_None);
        read.push_back(std::move(v));
        GDALClose(ds);
    }
    EXPECT_TRUE(read[0] == read[1]);
    EXPECT_EQ(read[1][199 * 300 + 0], static_cast<float>(values[0]))  // north-up: row 0 is the north
        << "cell (0, 0) is the first of the last row";
}

// The rows are written north-up (write_solver_rows, a row at a time into its flipped
// row), across tiles and on a grid larger than a tile in both directions.
TEST(WriteGeotiff, RowsAreWrittenNorthUp) {
    TempDir tmp;
    const GeoGrid geo = utm_grid(1100, 900);  // 3 x 2 tiles of 512 and overviews
    std::vector<double> z(geo.grid.cells());
    for (int j = 0; j < 900; ++j)
        for (int i = 0; i < 1100; ++i)
            z[static_cast<std::size_t>(j) * 1100 + i] = 1000.0 + 0.5 * i + 2.0 * j + std::sin(0.1 * i * j);
    write_geotiff(tmp.file("z.tif"), geo, z, BandInfo{"elevation", "m", -9999.0, {}, {}});

    GDALAllRegister();
    GDALDataset* ds = GDALDataset::Open(tmp.file("z.tif").c_str(), GDAL_OF_RASTER);
    ASSERT_NE(ds, nullptr);
    const auto pixel = [&](int col, int row) {
        float v = 0.0f;
        EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, col, row, 1, 1, &v, 1, 1, GDT_Float32, 0, 0,
                                                  nullptr),
                  CE_None);
        return v;
    };
    // Raster row 0 is the solver's northernmost row j = 899, the last row j = 0.
    EXPECT_EQ(pixel(7, 0), static_cast<float>(z[899 * 1100 + 7]));
    EXPECT_EQ(pixel(1099, 899), static_cast<float>(z[1099]));
    EXPECT_EQ(pixel(600, 300), static_cast<float>(z[(899 - 300) * 1100 + 600]));
    GDALClose(ds);
}

TEST(WriteGeotiff, ClassMapAsBytes) {
    TempDir tmp;
    const GeoGrid geo = utm_grid(8, 6);
    std::vector<double> classes(geo.grid.cells(), 0.0);
    classes[47] = 3.0;
    write_geotiff(tmp.file("hazard_class.tif"), geo, classes,
                  BandInfo{"hazard class", "", 255.0, {}, {}}, SampleType::uint8);
    const auto rows = testing::read_raw_rows(tmp.file("hazard_class.tif"));
    EXPECT_DOUBLE_EQ(rows[7], 3.0);  // solver (7, 5) = GeoTIFF row 0, column 7
    classes[1] = 2.5;
    expect_error<OutputError>(
        [&] {
            write_geotiff(tmp.file("c.tif"), geo, classes, BandInfo{"c", "", 255.0, {}, {}},
                          SampleType::uint8);
        },
        {"c.tif", "non-integer", "i=1, j=0"});
}

TEST(WriteGeotiff, NanIsRefusedAndNoFileIsLeft) {
    TempDir tmp;
    const GeoGrid geo = utm_grid(4, 3);
    std::vector<double> v(geo.grid.cells(), 1.0);
    v[1 * 4 + 2] = std::numeric_limits<double>::quiet_NaN();
    expect_error<OutputError>(
        [&] {
            write_geotiff(tmp.file("bad.tif"), geo, v, BandInfo{"v", "m", -9999.0, {}, {}});
        },
        {"bad.tif", "non-finite", "i=2, j=1"});
    EXPECT_FALSE(std::filesystem::exists(tmp.file("bad.tif")));
    EXPECT_FALSE(std::filesystem::exists(tmp.file("bad.tif.part")));
    v[6] = 1.0;
    expect_error<OutputError>(
        [&] { write_geotiff(tmp.file("no/such/dir.tif"), geo, v, BandInfo{}); },
        {"dir.tif", "does not exist"});
}

// Children of `node` named `name`, recursively.
void collect(CPLXMLNode* node, const std::string& name, std::vector<CPLXMLNode*>& out) {
    for (CPLXMLNode* c = node; c != nullptr; c = c->psNext) {
        if (c->eType == CXT_Element && name == c->pszValue) out.push_back(c);
        collect(c->psChild, name, out);
    }
}

TEST(WriteQml, PseudocolorClassesAreValidXml) {
    TempDir tmp;
    write_qml(tmp.file("max_depth.qml"), depth_ramp());
    CPLXMLNode* root = CPLParseXMLFile(tmp.file("max_depth.qml").c_str());
    ASSERT_NE(root, nullptr);
    std::vector<CPLXMLNode*> shader, items;
    collect(root, "colorrampshader", shader);
    ASSERT_EQ(shader.size(), 1u);
    EXPECT_STREQ(CPLGetXMLValue(shader[0], "colorRampType", ""), "DISCRETE");
    collect(root, "item", items);
    std::vector<std::string> values, labels;
    for (CPLXMLNode* n : items) {
        values.push_back(CPLGetXMLValue(n, "value", ""));
        labels.push_back(CPLGetXMLValue(n, "label", ""));
    }
    // Upper bounds of the classes (QGIS "Discrete"): below 0.1 transparent, ..., > 5 m.
    EXPECT_EQ(values, (std::vector<std::string>{"0.1", "0.5", "1", "2", "5", "inf"}));
    EXPECT_EQ(labels.back(), "> 5 m");
    EXPECT_EQ(labels[1], "0.1 - 0.5 m");
    EXPECT_STREQ(CPLGetXMLValue(items[0], "alpha", ""), "0");
    CPLDestroyXMLNode(root);
}

TEST(WriteQml, HazardClassesArePalettedWithLegendLabels) {
    TempDir tmp;
    write_qml(tmp.file("hazard_class.qml"), hazard_class_palette());
    CPLXMLNode* root = CPLParseXMLFile(tmp.file("hazard_class.qml").c_str());
    ASSERT_NE(root, nullptr);
    std::vector<CPLXMLNode*> renderer, entries;
    collect(root, "rasterrenderer", renderer);
    ASSERT_EQ(renderer.size(), 1u);
    EXPECT_STREQ(CPLGetXMLValue(renderer[0], "type", ""), "paletted");
    collect(root, "paletteEntry", entries);
    ASSERT_EQ(entries.size(), 4u);
    const char* expected[] = {"none", "low", "medium", "high"};
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(std::atoi(CPLGetXMLValue(entries[k], "value", "-1")), k);
        EXPECT_STREQ(CPLGetXMLValue(entries[k], "label", ""), expected[k]);
    }
    CPLDestroyXMLNode(root);
}

// A legend label with every character XML reserves reads back as written (the labels
// are escaped as attribute values).
TEST(WriteQml, LabelsWithMarkupCharactersReadBackAsWritten) {
    TempDir tmp;
    ColorRamp r = hazard_class_palette();
    const std::string label = "a < b & \"c\" > 'd'";
    r.stops[1].label = label;
    write_qml(tmp.file("labels.qml"), r);
    CPLXMLNode* root = CPLParseXMLFile(tmp.file("labels.qml").c_str());
    ASSERT_NE(root, nullptr);
    std::vector<CPLXMLNode*> entries;
    collect(root, "paletteEntry", entries);
    ASSERT_EQ(entries.size(), 4u);
    EXPECT_EQ(std::string(CPLGetXMLValue(entries[1], "label", "")), label);
    CPLDestroyXMLNode(root);
}

TEST(Style, DiscreteClassesMatchQgis) {
    const ColorRamp r = pressure_ramp();  // breaks 1, 3, 10, 30, 100 kPa
    EXPECT_EQ(color_at(r, 0.5).a, 0);     // below the first break: not drawn
    EXPECT_EQ(color_at(r, 1.0).a, 0);     // QGIS: 1.0 belongs to the item "<= 1"
    EXPECT_EQ(color_at(r, 2.0).r, r.stops[0].color.r);
    EXPECT_EQ(color_at(r, 30.0).g, r.stops[2].color.g);
    EXPECT_EQ(color_at(r, 500.0).b, r.stops[4].color.b);
    EXPECT_EQ(color_at(arrival_time_ramp(60.0), 0.0).a, 255);  // release cells at t = 0
}

// Hazard limits that coincide with the fixed breaks (1 and 10 kPa) or lie beyond them
// still give increasing classes, each once (no empty "10 - 10 kPa" class, no classes
// out of order).
TEST(Style, PressureClassesFromAnyHazardLimits) {
    for (const auto& breaks : std::vector<std::vector<double>>{{1.0, 1.0, 10.0, 10.0, 100.0},
                                                               {1.0, 50.0, 10.0, 300.0, 100.0}}) {
        const ColorRamp r = pressure_ramp(breaks);
        for (std::size_t k = 1; k < r.stops.size(); ++k)
            EXPECT_LT(r.stops[k - 1].value, r.stops[k].value) << k;
    }
    EXPECT_EQ(pressure_ramp({1.0, 1.0, 10.0, 10.0, 100.0}).stops.size(), 3u);
    const ColorRamp high = pressure_ramp({1.0, 50.0, 10.0, 300.0, 100.0});
    ASSERT_EQ(high.stops.size(), 5u);
    EXPECT_EQ(high.stops[2].value, 50.0);
    EXPECT_EQ(high.stops[4].value, 300.0);
}

TEST(Quicklook, HillshadeFacesTheNorthWestLight) {
    const Grid g{5, 5, 10.0, 10.0, 0.0, 0.0};
    std::vector<double> flat(g.cells(), 100.0), to_se(g.cells()), to_nw(g.cells());
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            to_se[j * 5 + i] = 10.0 * i - 10.0 * j;  // rises to the south-east: faces NW
            to_nw[j * 5 + i] = -10.0 * i + 10.0 * j;
        }
    EXPECT_NEAR(hillshade(g, flat)[12], std::sin(M_PI / 4), 1e-12);
    EXPECT_GT(hillshade(g, to_se)[12], 0.95);
    EXPECT_LT(hillshade(g, to_nw)[12], 0.05);
}

TEST(Quicklook, PngIsColouredWhereTheMapHasValues) {
    TempDir tmp;
    const GeoGrid geo = utm_grid(40, 30);
    std::vector<double> z(geo.grid.cells()), depth(geo.grid.cells(), 0.0);
    for (int j = 0; j < 30; ++j)
        for (int i = 0; i < 40; ++i) z[j * 40 + i] = 2.0 * i + 3.0 * j;
    depth[29 * 40 + 39] = 3.0;  // the north-east cell
    write_quicklook_png(tmp.file("max_depth.png"), geo, depth, z, depth_ramp(), -9999.0);
    GDALAllRegister();
    GDALDataset* ds = GDALDataset::Open(tmp.file("max_depth.png").c_str(), GDAL_OF_RASTER);
    ASSERT_NE(ds, nullptr);
    EXPECT_STREQ(ds->GetDriver()->GetDescription(), "PNG");
    EXPECT_GE(ds->GetRasterCount(), 3);
    EXPECT_LE(ds->GetRasterCount(), 4);
    EXPECT_EQ(ds->GetRasterXSize(), 40);
    auto pixel = [&](int band, int col, int row) {
        unsigned char v = 0;
        EXPECT_EQ(ds->GetRasterBand(band)->RasterIO(GF_Read, col, row, 1, 1, &v, 1, 1, GDT_Byte, 0,
                                                    0, nullptr),
                  CE_None);
        return int(v);
    };
    // Top-right pixel (north-east) is blue; the others are grey hillshade.
    EXPECT_GT(pixel(3, 39, 0), pixel(1, 39, 0) + 30);
    EXPECT_EQ(pixel(1, 0, 29), pixel(3, 0, 29));
    EXPECT_EQ(pixel(1, 39, 29), pixel(2, 39, 29));
    GDALClose(ds);
    EXPECT_FALSE(std::filesystem::exists(tmp.file("max_depth.png.aux.xml")));
}

TEST(Quicklook, CellsPerPixelKeepTheLongestSideWithinTheLimit) {
    const auto f = [](int nx, int ny) { return quicklook_cells_per_pixel(Grid{nx, ny, 1.0, 1.0, 0.0, 0.0}); };
    EXPECT_EQ(f(kQuicklookMaxPixels, 10), 1);
    EXPECT_EQ(f(10, kQuicklookMaxPixels), 1);
    EXPECT_EQ(f(kQuicklookMaxPixels + 1, 10), 2);
    EXPECT_EQ(f(10, 2 * kQuicklookMaxPixels), 2);
    EXPECT_EQ(f(2 * kQuicklookMaxPixels + 1, 3), 3);
}

// The pixels' hillshade made once (quicklook_shade): the mean of each block's cells, the
// cut-short blocks at the edges included; a quick-look drawn over it is the file drawn
// over the cells' hillshade, byte for byte.
TEST(Quicklook, ShadeOfThePixelsIsTheMeanOfTheirCells) {
    TempDir tmp;
    const int nx = 2 * kQuicklookMaxPixels + 4, ny = 5;  // 3 x 3 cells a pixel, 1367 x 2
    GeoGrid geo = utm_grid(nx, ny);
    std::vector<double> shade(geo.grid.cells()), depth(geo.grid.cells(), -9999.0);
    for (std::size_t k = 0; k < shade.size(); ++k) shade[k] = static_cast<double>(k % 101) / 100.0;
    for (std::size_t k = 0; k < depth.size(); k += 13) depth[k] = 0.01 * static_cast<double>(k % 301);
    const QuicklookShade q = quicklook_shade(geo.grid, shade);
    ASSERT_EQ(q.cells_per_pixel, 3);
    ASSERT_EQ(q.tone.size(), 1367u * 2u);
    const auto cell = [&](int i, int j) { return shade[static_cast<std::size_t>(j) * nx + i]; };
    double first = 0.0, corner = 0.0;
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) first += cell(i, j);
    for (int j = 3; j < 5; ++j)
        for (int i = nx - 2; i < nx; ++i) corner += cell(i, j);
    EXPECT_DOUBLE_EQ(q.tone[0], first / 9.0);
    EXPECT_DOUBLE_EQ(q.tone[1367 + 1366], corner / 4.0) << "the cut-short corner block";
    write_quicklook_png_over(tmp.file("cells.png"), geo, depth, shade, depth_ramp(), -9999.0);
    write_quicklook_png_over(tmp.file("pixels.png"), geo, depth, q, depth_ramp(), -9999.0);
    std::ifstream a(tmp.file("cells.png"), std::ios::binary), b(tmp.file("pixels.png"), std::ios::binary);
    const std::string fa((std::istreambuf_iterator<char>(a)), {}), fb((std::istreambuf_iterator<char>(b)), {});
    EXPECT_FALSE(fa.empty());
    EXPECT_TRUE(fa == fb);
    // A shade made for another grid is refused.
    EXPECT_THROW(write_quicklook_png_over(tmp.file("other.png"), utm_grid(4, 1), {1.0, 1.0, 1.0, 1.0}, q,
                                          depth_ramp(), -9999.0),
                 OutputError);
}

// Cells outside the DEM's data are drawn as the hatch (no_data_tone), whatever the filled
// terrain's hillshade there; a map's colour still shows over them; the cells with data
// are drawn as without the mask, byte for byte. In blocks of cells a pixel is hatched only
// when every cell of its block is outside.
TEST(Quicklook, CellsOutsideTheDemsDataAreHatchedNotShaded) {
    TempDir tmp;
    const int nx = 40, ny = 30;
    const GeoGrid geo = utm_grid(nx, ny);
    std::vector<double> z(geo.grid.cells()), depth(geo.grid.cells(), -9999.0);
    std::vector<std::uint8_t> outside(geo.grid.cells(), 0);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            z[j * nx + i] = 2.0 * i + 3.0 * j + 40.0 * std::sin(0.3 * i * j);  // shades differ
            outside[j * nx + i] = i >= 30 ? 1 : 0;
        }
    depth[10 * nx + 35] = 3.0;  // flow drawn over a cell without data
    const std::vector<double> shade = hillshade(geo.grid, z);
    write_quicklook_png_over(tmp.file("masked.png"), geo, depth,
                             quicklook_shade(geo.grid, shade, outside), depth_ramp(), -9999.0);
    write_quicklook_png_over(tmp.file("plain.png"), geo, depth, quicklook_shade(geo.grid, shade),
                             depth_ramp(), -9999.0);
    GDALAllRegister();
    GDALDataset* masked = GDALDataset::Open(tmp.file("masked.png").c_str(), GDAL_OF_RASTER);
    GDALDataset* plain = GDALDataset::Open(tmp.file("plain.png").c_str(), GDAL_OF_RASTER);
    ASSERT_NE(masked, nullptr);
    ASSERT_NE(plain, nullptr);
    // Pixel (band, i, j) with j counted from the south, as the solver's rows.
    const auto pixel = [&](GDALDataset* ds, int band, int i, int j) {
        unsigned char v = 0;
        EXPECT_EQ(ds->GetRasterBand(band)->RasterIO(GF_Read, i, ny - 1 - j, 1, 1, &v, 1, 1,
                                                    GDT_Byte, 0, 0, nullptr),
                  CE_None);
        return int(v);
    };
    int lines = 0, ground = 0, shaded_apart = 0;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            if (i < 30) {
                for (int b = 1; b <= 3; ++b)
                    ASSERT_EQ(pixel(masked, b, i, j), pixel(plain, b, i, j)) << i << ", " << j;
                continue;
            }
            if (i == 35 && j == 10) continue;
            const int expected = static_cast<int>(std::lround(255.0 * no_data_tone(i, j)));
            for (int b = 1; b <= 3; ++b)
                ASSERT_EQ(pixel(masked, b, i, j), expected) << i << ", " << j;
            (no_data_tone(i, j) == kNoDataLine ? lines : ground) += 1;
            shaded_apart += pixel(plain, 1, i, j) != expected;
        }
    EXPECT_GT(lines, 10);
    EXPECT_GT(ground, 10);
    EXPECT_GT(shaded_apart, 50) << "the hillshade there would have looked the same";
    EXPECT_GT(pixel(masked, 3, 35, 10), pixel(masked, 1, 35, 10) + 30) << "the flow's blue";
    GDALClose(masked);
    GDALClose(plain);

    // Blocks of 3 x 3 cells: the first three blocks wholly outside, the fourth mixed.
    const GeoGrid wide = utm_grid(2 * kQuicklookMaxPixels + 4, 5);
    std::vector<std::uint8_t> left(wide.grid.cells(), 0);
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 10; ++i) left[static_cast<std::size_t>(j) * wide.grid.nx + i] = 1;
    const QuicklookShade q =
        quicklook_shade(wide.grid, std::vector<double>(wide.grid.cells(), 0.5), left);
    ASSERT_EQ(q.no_data.size(), q.tone.size());
    EXPECT_EQ(q.no_data[0], 1);
    EXPECT_EQ(q.no_data[2], 1);
    EXPECT_EQ(q.no_data[3], 0) << "a block with measured cells shows their terrain";
    EXPECT_EQ(q.no_data[1367 + 2], 1) << "the second row of blocks, cut short";
    EXPECT_TRUE(
        quicklook_shade(wide.grid, std::vector<double>(wide.grid.cells(), 0.5)).no_data.empty());
}

// A grid longer than kQuicklookMaxPixels: 3 x 3 cells a pixel. A block's colour is that
// of its largest valid value (its smallest for arrival times), so that one cell of flow
// shows; a block without one is the grey of its mean hillshade.
TEST(Quicklook, LargeGridIsDrawnInBlocksShowingTheirLargestValue) {
    TempDir tmp;
    const int nx = 2 * kQuicklookMaxPixels + 4, ny = 5;  // 1367 x 2 pixels, the last ones cut short
    ASSERT_EQ(quicklook_cells_per_pixel(Grid{nx, ny, 1.0, 1.0, 0.0, 0.0}), 3);
    GeoGrid geo = utm_grid(nx, ny);
    const double nodata = -9999.0;
    std::vector<double> shade(geo.grid.cells(), 0.5), depth(geo.grid.cells(), nodata);
    const auto at = [&](int i, int j) -> double& { return depth[static_cast<std::size_t>(j) * nx + i]; };
    // Pixel (10, south row): one cell of 3 m among nodata. Pixel (20, south row): 0.2 m
    // and 3 m. Pixel (30, south row): 0.2 m alone. Pixel (1366, north row): the cut-short
    // corner block (2 x 2 cells), one cell of 3 m.
    at(31, 1) = 3.0;
    at(60, 0) = 0.2, at(62, 2) = 3.0;
    at(91, 2) = 0.2;
    at(nx - 1, ny - 1) = 3.0;
    shade[static_cast<std::size_t>(4) * nx + 1] = 1.0;  // pixel (0, north row): 0.5 + 0.5 / 6
    // The same values one pixel per cell, as references for the colours.
    const GeoGrid one = utm_grid(4, 1);
    write_quicklook_png_over(tmp.file("blocks.png"), geo, depth, shade, depth_ramp(), nodata);
    write_quicklook_png_over(tmp.file("cells.png"), one, {3.0, 0.2, nodata, nodata},
                             {0.5, 0.5, 0.5, 0.5 + 0.5 / 6.0}, depth_ramp(), nodata);
    GDALAllRegister();
    GDALDataset* blocks = GDALDataset::Open(tmp.file("blocks.png").c_str(), GDAL_OF_RASTER);
    GDALDataset* cells = GDALDataset::Open(tmp.file("cells.png").c_str(), GDAL_OF_RASTER);
    ASSERT_NE(blocks, nullptr);
    ASSERT_NE(cells, nullptr);
    EXPECT_EQ(blocks->GetRasterXSize(), 1367);
    EXPECT_EQ(blocks->GetRasterYSize(), 2);
    const auto rgb = [](GDALDataset* ds, int col, int row) {
        std::array<int, 3> c{};
        for (int b = 0; b < 3; ++b) {
            unsigned char v = 0;
            EXPECT_EQ(ds->GetRasterBand(b + 1)->RasterIO(GF_Read, col, row, 1, 1, &v, 1, 1, GDT_Byte,
                                                         0, 0, nullptr),
                      CE_None);
            c[static_cast<std::size_t>(b)] = v;
        }
        return c;
    };
    // PNG row 1 is the south row of blocks, row 0 the north one.
    const auto deep = rgb(cells, 0, 0), shallow = rgb(cells, 1, 0), grey = rgb(cells, 2, 0);
    EXPECT_NE(deep, shallow);
    EXPECT_NE(deep, grey);
    EXPECT_EQ(rgb(blocks, 10, 1), deep);
    EXPECT_EQ(rgb(blocks, 20, 1), deep);
    EXPECT_EQ(rgb(blocks, 30, 1), shallow);
    EXPECT_EQ(rgb(blocks, 1366, 0), deep);
    EXPECT_EQ(rgb(blocks, 40, 1), grey);
    EXPECT_EQ(rgb(blocks, 0, 0), rgb(cells, 3, 0));  // the hillshade averaged over 3 x 2 cells
    GDALClose(blocks);

    // Arrival times: the earliest of a block (0.2 s, not 3 s, at pixel 20).
    write_quicklook_png_over(tmp.file("arrival.png"), geo, depth, shade, arrival_time_ramp(5.0),
                             nodata, QuicklookBlock::minimum);
    write_quicklook_png_over(tmp.file("arrival_cells.png"), one, {3.0, 0.2, nodata, nodata},
                             {0.5, 0.5, 0.5, 0.5}, arrival_time_ramp(5.0), nodata);
    GDALDataset* arrival = GDALDataset::Open(tmp.file("arrival.png").c_str(), GDAL_OF_RASTER);
    GDALDataset* arrival_cells = GDALDataset::Open(tmp.file("arrival_cells.png").c_str(), GDAL_OF_RASTER);
    ASSERT_NE(arrival, nullptr);
    ASSERT_NE(arrival_cells, nullptr);
    EXPECT_NE(rgb(arrival_cells, 0, 0), rgb(arrival_cells, 1, 0));
    EXPECT_EQ(rgb(arrival, 20, 1), rgb(arrival_cells, 1, 0));
    EXPECT_EQ(rgb(arrival, 10, 1), rgb(arrival_cells, 0, 0));
    GDALClose(arrival);
    GDALClose(arrival_cells);
    GDALClose(cells);
}

}  // namespace
}  // namespace avalanche::gis
