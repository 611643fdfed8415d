// STYLE.md convention 10: a ramp rising to the north-east, so that a map flipped
// north-south or east-west cannot pass.
#include <gtest/gtest.h>

#include <algorithm>

#include "avalanche/gis/dem.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "gis_test_support.hpp"

namespace avalanche::gis {
namespace {

using testing::TempDir;

// 5 columns x 4 rows of 10 m, west edge 500000, north edge 5200040 (UTM 32N).
// Value = 10*col + 100*(3 - row): rises by 10 per column east and 100 per row north.
constexpr int kW = 5, kH = 4;
constexpr double kCell = 10.0, kWest = 500000.0, kNorth = 5200040.0;
double ramp(int col, int row) { return 10.0 * col + 100.0 * (kH - 1 - row); }

void write_ramp(const std::string& path) {
    testing::write_raw_geotiff(path, kW, kH, {kWest, kCell, 0, kNorth, 0, -kCell}, "EPSG:32632",
                               ramp);
}

TEST(Orientation, RampReadsWithTheMaximumAtTheNorthEastCell) {
    TempDir tmp;
    write_ramp(tmp.file("ramp.tif"));
    const Dem dem = load_dem({tmp.file("ramp.tif")});
    const Grid& g = dem.geo.grid;
    ASSERT_EQ(g.nx, kW);
    ASSERT_EQ(g.ny, kH);
    EXPECT_DOUBLE_EQ(g.dx, kCell);
    EXPECT_DOUBLE_EQ(g.x0, kWest);
    EXPECT_DOUBLE_EQ(g.y0, kNorth - kH * kCell);  // south edge
    auto z = [&](int i, int j) { return dem.z[static_cast<std::size_t>(j) * g.nx + i]; };
    EXPECT_DOUBLE_EQ(z(g.nx - 1, g.ny - 1), *std::max_element(dem.z.begin(), dem.z.end()));
    EXPECT_DOUBLE_EQ(z(0, 0), 0.0);                         // south-west: lowest
    EXPECT_DOUBLE_EQ(z(g.nx - 1, g.ny - 1), 40.0 + 300.0);  // north-east: highest
    EXPECT_DOUBLE_EQ(z(1, 0), 10.0);                        // one cell east of SW
    EXPECT_DOUBLE_EQ(z(0, 1), 100.0);                       // one cell north of SW
    EXPECT_EQ(dem.filled_voids, 0);
    EXPECT_EQ(dem.geo.epsg(), 32632);
}

TEST(Orientation, GeotransformIsNorthUp) {
    GeoGrid geo{Grid{kW, kH, kCell, kCell, kWest, kNorth - kH * kCell}, ""};
    const auto gt = geo.geotransform();
    EXPECT_DOUBLE_EQ(gt[0], kWest);
    EXPECT_DOUBLE_EQ(gt[3], kNorth);
    EXPECT_DOUBLE_EQ(gt[1], kCell);
    EXPECT_DOUBLE_EQ(gt[5], -kCell);
}

TEST(Orientation, WrittenDemHasTheSameGeoTiffRowsAsTheSource) {
    TempDir tmp;
    write_ramp(tmp.file("ramp.tif"));
    const Dem dem = load_dem({tmp.file("ramp.tif")});
    write_dem(tmp.file("out.tif"), dem);
    int w = 0, h = 0;
    const auto source = testing::read_raw_rows(tmp.file("ramp.tif"));
    const auto written = testing::read_raw_rows(tmp.file("out.tif"), &w, &h);
    ASSERT_EQ(w, kW);
    ASSERT_EQ(h, kH);
    EXPECT_EQ(written, source);
    EXPECT_DOUBLE_EQ(written[kW - 1], 340.0);  // GeoTIFF row 0 (north), last column (east)
}

TEST(Orientation, WrittenMapHasTheKnownCornerValues) {
    // A solver field equal to 1000*i + j: the GeoTIFF's top-left (north-west) pixel is
    // i = 0, j = ny-1, and its bottom-right (south-east) pixel is i = nx-1, j = 0.
    TempDir tmp;
    GeoGrid geo{Grid{kW, kH, kCell, kCell, kWest, kNorth - kH * kCell}, ""};
    geo.crs_wkt = utm_crs_wkt_for(9.0, 47.0);
    std::vector<double> v(geo.grid.cells());
    for (int j = 0; j < kH; ++j)
        for (int i = 0; i < kW; ++i) v[static_cast<std::size_t>(j) * kW + i] = 1000.0 * i + j;
    write_geotiff(tmp.file("map.tif"), geo, v, BandInfo{"test", "m", -1.0, {}, {}});
    const auto rows = testing::read_raw_rows(tmp.file("map.tif"));
    EXPECT_DOUBLE_EQ(rows.front(), kH - 1);                      // north-west
    EXPECT_DOUBLE_EQ(rows.back(), 1000.0 * (kW - 1));            // south-east
    EXPECT_DOUBLE_EQ(rows[kW - 1], 1000.0 * (kW - 1) + kH - 1);  // north-east
}

TEST(Orientation, AsciiGridFixtureReadsNorthEastUp) {
    // tests/data/gis/ramp_ne.asc is human-readable: its first line is the north row.
    const Dem dem = load_dem({testing::fixture("ramp_ne.asc")}, DemOptions{"EPSG:32632"});
    const Grid& g = dem.geo.grid;
    auto z = [&](int i, int j) { return dem.z[static_cast<std::size_t>(j) * g.nx + i]; };
    EXPECT_DOUBLE_EQ(z(g.nx - 1, g.ny - 1), *std::max_element(dem.z.begin(), dem.z.end()));
    EXPECT_DOUBLE_EQ(z(0, 0), *std::min_element(dem.z.begin(), dem.z.end()));
    EXPECT_LT(z(g.nx - 1, 0), z(0, g.ny - 1));  // the north rises faster than the east
}

}  // namespace
}  // namespace avalanche::gis
