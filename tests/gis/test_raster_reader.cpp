// read_geotiff is the inverse of write_geotiff: same grid, CRS, nodata and values in
// solver orientation. The fixture rises to the north-east, so a flipped read fails.
#include <gtest/gtest.h>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/raster_reader.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "gis_test_support.hpp"

namespace avalanche::gis {
namespace {

using testing::TempDir;

TEST(ReadGeotiff, RoundTripsWriteGeotiffInSolverOrientation) {
    TempDir tmp;
    const GeoGrid geo{Grid{7, 5, 2.0, 3.0, 600000.0, 5200000.0}, utm_crs_wkt_for(9.0, 47.0)};
    std::vector<double> ramp(geo.grid.cells());
    for (int j = 0; j < geo.grid.ny; ++j)
        for (int i = 0; i < geo.grid.nx; ++i) ramp[j * geo.grid.nx + i] = 10.0 * j + i;
    ramp[3] = -9999.0;
    write_geotiff(tmp.file("ramp.tif"), geo, ramp, BandInfo{"ramp", "m", -9999.0, {}, {}},
                  SampleType::float64);

    const RasterData r = read_geotiff(tmp.file("ramp.tif"));
    EXPECT_EQ(r.geo.grid.nx, 7);
    EXPECT_EQ(r.geo.grid.ny, 5);
    EXPECT_DOUBLE_EQ(r.geo.grid.dx, 2.0);
    EXPECT_DOUBLE_EQ(r.geo.grid.dy, 3.0);
    EXPECT_DOUBLE_EQ(r.geo.grid.x0, 600000.0);
    EXPECT_DOUBLE_EQ(r.geo.grid.y0, 5200000.0);
    EXPECT_EQ(r.geo.epsg(), 32632);
    ASSERT_TRUE(r.nodata.has_value());
    EXPECT_DOUBLE_EQ(*r.nodata, -9999.0);
    EXPECT_EQ(r.units, "m");
    EXPECT_EQ(r.values, ramp);  // j = 0 is the south row, as written
}

TEST(ReadGeotiff, WithoutCrsTheWktIsEmpty) {
    TempDir tmp;
    const GeoGrid geo{Grid{3, 2, 0.5, 0.5, 0.0, 0.0}, ""};
    write_geotiff(tmp.file("chute.tif"), geo, {1, 2, 3, 4, 5, 6}, BandInfo{"x", "m", -1.0, {}, {}});
    const RasterData r = read_geotiff(tmp.file("chute.tif"));
    EXPECT_TRUE(r.geo.crs_wkt.empty());
    EXPECT_EQ(r.values, (std::vector<double>{1, 2, 3, 4, 5, 6}));
}

TEST(ReadGeotiff, MissingFileIsAnInputErrorNamingIt) {
    try {
        read_geotiff("/nonexistent/max_depth.tif");
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/max_depth.tif"), std::string::npos);
    }
}

}  // namespace
}  // namespace avalanche::gis
