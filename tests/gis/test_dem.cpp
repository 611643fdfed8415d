// load_dem on real and synthetic DEMs: reprojection, mosaics, voids, refusals.
#include <cpl_conv.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/dem.hpp"
#include "geographic_fixture.hpp"
#include "gis_test_support.hpp"
#include "support/same_bits.hpp"

namespace avalanche::gis {
namespace {

using testing::expect_error;
using testing::TempDir;

constexpr double kAvaKotMin = 1052.15, kAvaKotMax = 2206.98;  // data/README.md

bool all_finite(const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

TEST(UtmZone, FromLongitudeAndLatitude) {
    EXPECT_EQ(utm_epsg_for(11.4, 47.3), 32632);    // Tyrol
    EXPECT_EQ(utm_epsg_for(10.39, 47.26), 32632);  // avaKot
    EXPECT_EQ(utm_epsg_for(5.99, 45.0), 32631);
    EXPECT_EQ(utm_epsg_for(6.0, 45.0), 32632);     // a zone starts at its west edge
    EXPECT_EQ(utm_epsg_for(-70.0, -33.0), 32719);  // Andes, south
    EXPECT_EQ(utm_epsg_for(179.99, 10.0), 32660);
    EXPECT_EQ(utm_epsg_for(180.0, 10.0), 32601);
    EXPECT_THROW(utm_epsg_for(10.0, 86.0), ConfigError);
}

TEST(LoadDem, ProjectedDemKeepsItsCellsWithoutResampling) {
    const std::string path = testing::avaKot("avaKot_dem.tif");
    const Dem dem = load_dem({path});
    const Grid& g = dem.geo.grid;
    EXPECT_EQ(g.nx, 439);
    EXPECT_EQ(g.ny, 517);
    EXPECT_NEAR(g.dx, 4.997688906601, 1e-9);
    EXPECT_NEAR(g.x0, 176973.437998359207995, 1e-6);
    EXPECT_NEAR(g.y0 + g.ny * g.dy, 378821.641540875658393, 1e-6);
    // The file's WKT has no EPSG ID and PROJ matches EPSG:31287 at only 50 %: the CRS is
    // kept as the file states it, without an EPSG code.
    EXPECT_NE(dem.geo.crs_label().find("MGI / Austria Lambert"), std::string::npos);
    // Same values as the file where it has data (solver row j = GeoTIFF row ny-1-j).
    const auto rows = testing::read_raw_rows(path);
    int compared = 0;
    for (int j = 0; j < g.ny; j += 7)
        for (int i = 0; i < g.nx; i += 5) {
            const double file = rows[static_cast<std::size_t>(g.ny - 1 - j) * g.nx + i];
            if (file == -9999.0) continue;
            ASSERT_EQ(dem.z[static_cast<std::size_t>(j) * g.nx + i], file) << i << "," << j;
            ++compared;
        }
    EXPECT_GT(compared, 1000);
    // The footprint is a rotated rectangle: about 40 % of the box is outside it.
    EXPECT_EQ(dem.filled_voids, 90023);  // -9999 cells of the file
    EXPECT_EQ(dem.filled_outside + dem.filled_holes, dem.filled_voids);
    EXPECT_TRUE(all_finite(dem.z));
    EXPECT_NEAR(dem.z_min, kAvaKotMin, 0.01);
    EXPECT_NEAR(dem.z_max, kAvaKotMax, 0.01);
    EXPECT_NE(dem.description_of_steps.find("no resampling"), std::string::npos);
}

TEST(LoadDem, GeographicTilesAreMosaickedIntoTheUtmZone) {
    TempDir tmp;
    testing::make_geographic_dem(tmp);
    const Dem dem = load_dem({tmp.file("west.tif"), tmp.file("east.tif")});
    EXPECT_EQ(dem.geo.epsg(), 32632);
    EXPECT_NEAR(dem.geo.grid.dx, 30.0, 1e-9);  // 1 arc-second of latitude, rounded
    EXPECT_DOUBLE_EQ(dem.geo.grid.dy, dem.geo.grid.dx);
    EXPECT_GT(dem.filled_voids, 0);
    EXPECT_EQ(dem.filled_outside + dem.filled_holes, dem.filled_voids);
    EXPECT_EQ(std::count(dem.filled_mask.begin(), dem.filled_mask.end(), 0),
              static_cast<long>(dem.geo.grid.cells()) - dem.filled_voids);
    EXPECT_TRUE(all_finite(dem.z));
    // Int16 rounding and interpolation stay within the source range.
    const auto [lo, hi] = std::minmax_element(dem.z.begin(), dem.z.end());
    EXPECT_GE(*lo, kAvaKotMin - 1.0);
    EXPECT_LE(*hi, kAvaKotMax + 1.0);
    EXPECT_GT(dem.z_max - dem.z_min, 900.0) << dem.description_of_steps;

    // The two tiles give exactly the grid and values of the unsplit file.
    const Dem whole = load_dem({tmp.file("geo.tif")});
    EXPECT_EQ(whole.geo.grid.nx, dem.geo.grid.nx);
    EXPECT_EQ(whole.geo.grid.ny, dem.geo.grid.ny);
    EXPECT_DOUBLE_EQ(whole.geo.grid.x0, dem.geo.grid.x0);
    EXPECT_DOUBLE_EQ(whole.geo.grid.y0, dem.geo.grid.y0);
    double worst = 0.0;
    for (std::size_t k = 0; k < dem.z.size(); ++k)
        if (dem.filled_mask[k] == 0 && whole.filled_mask[k] == 0)
            worst = std::max(worst, std::abs(dem.z[k] - whole.z[k]));
    EXPECT_LT(worst, 1e-6);
}

TEST(LoadDem, TilesInDifferentCrsAreWarpedTogether) {
    TempDir tmp;
    testing::make_geographic_dem(tmp);
    // The east tile goes back to Austria Lambert at 20 m: two CRSs, two resolutions.
    testing::run_gdalwarp(tmp.file("east.tif"), tmp.file("east_lambert.tif"),
                          {"-t_srs", "EPSG:31287", "-tr", "20", "20", "-r", "bilinear"});
    const Dem mixed = load_dem({tmp.file("west.tif"), tmp.file("east_lambert.tif")});
    const Dem whole = load_dem({tmp.file("geo.tif")});
    EXPECT_EQ(mixed.geo.epsg(), 32632);  // chosen from the first (geographic) tile
    EXPECT_DOUBLE_EQ(mixed.geo.grid.dx, 30.0);
    const auto measured = [](const Dem& d) {
        return std::count(d.filled_mask.begin(), d.filled_mask.end(), 0);
    };
    // Both halves are there: about as many measured cells as from the unsplit file.
    EXPECT_NEAR(static_cast<double>(measured(mixed)), static_cast<double>(measured(whole)),
                0.05 * static_cast<double>(measured(whole)));
    EXPECT_NEAR(mixed.z_max, whole.z_max, 15.0);
}

// Tiles of one CRS stored in different types (an Int16 tile beside a Float32 one) make
// one mosaic: the grid and elevations of the same area in one file.
TEST(LoadDem, TilesOfDifferentDataTypesAreMosaickedTogether) {
    TempDir tmp;
    const auto z = [](int col, int row) { return 1000.0 + 3.0 * col + 7.0 * row; };  // whole m
    const auto gt = [](double x0) {
        return std::array<double, 6>{x0, 10.0, 0.0, 5000.0, 0.0, -10.0};
    };
    testing::write_raw_geotiff(tmp.file("whole.tif"), 40, 20, gt(1000.0), "EPSG:31287", z);
    testing::write_raw_geotiff(tmp.file("west.tif"), 20, 20, gt(1000.0), "EPSG:31287", z,
                               GDT_Float32);
    testing::write_raw_geotiff(
        tmp.file("east.tif"), 20, 20, gt(1200.0), "EPSG:31287",
        [&](int col, int row) { return z(col + 20, row); }, GDT_Int16);
    const Dem whole = load_dem({tmp.file("whole.tif")});
    const Dem tiled = load_dem({tmp.file("west.tif"), tmp.file("east.tif")});
    EXPECT_EQ(tiled.geo.grid.nx, whole.geo.grid.nx);
    EXPECT_EQ(tiled.geo.grid.ny, whole.geo.grid.ny);
    EXPECT_EQ(tiled.filled_voids, 0);
    EXPECT_EQ(tiled.z, whole.z);
}

// Tiles without a CRS, given one by the option, are mosaicked through views that carry
// it (this once crashed: the mosaic outlived the views it reads).
TEST(LoadDem, TilesWithoutCrsAreMosaickedInTheGivenCrs) {
    TempDir tmp;
    const auto z = [](int col, int row) { return 1000.0 + 3.0 * col + 7.0 * row; };
    const auto gt = [](double x0) {
        return std::array<double, 6>{x0, 10.0, 0.0, 5000.0, 0.0, -10.0};
    };
    testing::write_raw_geotiff(tmp.file("whole.tif"), 40, 20, gt(1000.0), "EPSG:31287", z);
    testing::write_raw_geotiff(tmp.file("west.tif"), 20, 20, gt(1000.0), "", z);
    testing::write_raw_geotiff(tmp.file("east.tif"), 20, 20, gt(1200.0), "",
                               [&](int col, int row) { return z(col + 20, row); });
    DemOptions opts;
    opts.crs = "EPSG:31287";
    const Dem tiled = load_dem({tmp.file("west.tif"), tmp.file("east.tif")}, opts);
    EXPECT_EQ(tiled.geo.epsg(), 31287);
    EXPECT_EQ(tiled.filled_voids, 0);
    EXPECT_EQ(tiled.z, load_dem({tmp.file("whole.tif")}).z);
}

// Elevations stored scaled (decimetres in integers, with a scale in the band) would make
// terrain ten times too tall if read as they are stored.
TEST(LoadDem, ScaledElevationsAreRefused) {
    TempDir tmp;
    const std::string path = tmp.file("decimetres.tif");
    testing::write_raw_geotiff(
        path, 20, 20, {1000.0, 10.0, 0.0, 5000.0, 0.0, -10.0}, "EPSG:31287",
        [](int col, int row) { return 10000.0 + 30.0 * col + 70.0 * row; }, GDT_UInt16);
    GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE);
    ASSERT_NE(ds, nullptr);
    ds->GetRasterBand(1)->SetScale(0.1);
    GDALClose(ds);
    expect_error<InputError>([&] { load_dem({path}); },
                             {path, "scaled elevations (scale 0.1", "gdal_translate -unscale"});
}

TEST(LoadDem, UserCrsAndCellSizeReprojectAProjectedDem) {
    DemOptions opts;
    opts.crs = "EPSG:32632";
    opts.cell_size = 10.0;
    const Dem dem = load_dem({testing::avaKot("avaKot_dem.tif")}, opts);
    EXPECT_EQ(dem.geo.epsg(), 32632);
    EXPECT_DOUBLE_EQ(dem.geo.grid.dx, 10.0);
    EXPECT_DOUBLE_EQ(std::fmod(dem.geo.grid.x0, 10.0), 0.0);  // aligned on the cell size
    EXPECT_NEAR(dem.z_min, kAvaKotMin, 15.0);
    EXPECT_LE(dem.z_max, kAvaKotMax + 1e-6);
}

// GDAL's warp kernel on several threads (the run's) gives the cells of one thread:
// reprojected and resampled, void filled, to the bit.
TEST(LoadDem, WarpedCellsAreTheSameOnAnyNumberOfThreads) {
    DemOptions opts;
    opts.crs = "EPSG:32632";
    opts.cell_size = 2.5;
    const Dem one = load_dem({testing::avaKot("avaKot_dem.tif")}, opts);
    opts.threads = 3;
    const Dem three = load_dem({testing::avaKot("avaKot_dem.tif")}, opts);
    ASSERT_EQ(one.z.size(), three.z.size());
    ASSERT_GT(one.z.size(), 1000000u);
    EXPECT_TRUE(test::same_bits(one.z, three.z));
    EXPECT_EQ(one.filled_mask, three.filled_mask);
}

// The void fill interpolates in bands of rows on the run's threads (void_fill.cpp): a
// band with 65 rows of context on either side gives its rows the whole grid's values.
// Holes of every size scattered over a projected DEM (so that the grid is its cells:
// nothing is resampled) and a wedge of voids at its border, on 1, 2 and 5 threads (5
// bands of 84 rows, whose edges cross holes and the wedge), to the bit. (With 40 rows of
// context the bands differ here; with 63, one less than the reach, in the test above.)
TEST(LoadDem, VoidsAreFilledTheSameOnAnyNumberOfThreads) {
    TempDir tmp;
    constexpr int kW = 300, kH = 420;
    const auto hole = [](int c, int r) {
        if (c + r < 60) return true;                                   // the wedge at a corner
        // A hole wider than twice the interpolation's reach (64 cells) across the bands'
        // edges at rows 168 and 210: its inner cells take values from data up to that
        // far away, its middle is beyond it (extended from the filled cells).
        if (c >= 100 && c < 240 && r >= 110 && r < 250) return true;
        const int bc = c / 37, br = r / 29;                            // blocks of cells
        const unsigned hash = static_cast<unsigned>(bc * 7919 + br * 104729) % 11u;
        if (hash == 0) return (c % 37) < 20 && (r % 29) < 25;          // large holes
        return (static_cast<unsigned>(c * 31 + r * 17) % 97u) == 0;  // single cells
    };
    testing::write_raw_geotiff(tmp.file("holes.tif"), kW, kH, {600000, 10, 0, 5200000 + 10 * kH, 0, -10},
                               "EPSG:32632", [&](int c, int r) {
                                   const double z = 1000.0 + 2.0 * c - 3.0 * r + 5.0 * std::sin(0.05 * c * r);
                                   return hole(c, r) ? std::numeric_limits<double>::quiet_NaN() : z;
                               });
    DemOptions opts;
    const Dem one = load_dem({tmp.file("holes.tif")}, opts);
    ASSERT_EQ(one.z.size(), static_cast<std::size_t>(kW) * kH);
    EXPECT_GT(one.filled_holes, 2000);
    EXPECT_GT(one.filled_outside, 1000);
    EXPECT_TRUE(all_finite(one.z));
    for (int threads : {2, 5}) {
        opts.threads = threads;
        const Dem many = load_dem({tmp.file("holes.tif")}, opts);
        ASSERT_EQ(one.z.size(), many.z.size());
        EXPECT_TRUE(test::same_bits(one.z, many.z)) << threads;
        EXPECT_EQ(one.filled_mask, many.filled_mask) << threads;
    }
}

TEST(LoadDem, DemWithoutCrsNeedsTheCrsOption) {
    TempDir tmp;
    testing::write_raw_geotiff(tmp.file("nocrs.tif"), 6, 5, {600000, 10, 0, 5200050, 0, -10}, "",
                               [](int c, int r) { return 1000.0 + c + 2 * r; });
    expect_error<InputError>([&] { load_dem({tmp.file("nocrs.tif")}); },
                             {"nocrs.tif", "no coordinate reference system"});
    const Dem dem = load_dem({tmp.file("nocrs.tif")}, DemOptions{"EPSG:32633"});
    EXPECT_EQ(dem.geo.epsg(), 32633);
    EXPECT_EQ(dem.geo.grid.nx, 6);
}

TEST(LoadDem, AllNodataIsRefused) {
    TempDir tmp;
    testing::write_raw_geotiff(
        tmp.file("empty.tif"), 4, 4, {600000, 10, 0, 5200040, 0, -10}, "EPSG:32632",
        [](int, int) { return -9999.0; }, GDT_Float32, -9999.0);
    expect_error<InputError>([&] { load_dem({tmp.file("empty.tif")}); },
                             {"empty.tif", "no valid elevation"});
}

TEST(LoadDem, TruncatedAndForeignFilesAreRefused) {
    TempDir tmp;
    const std::string cut = tmp.file("truncated.tif");
    std::filesystem::copy_file(testing::avaKot("avaKot_dem.tif"), cut);
    std::filesystem::resize_file(cut, std::filesystem::file_size(cut) / 2);
    expect_error<InputError>([&] { load_dem({cut}); }, {"truncated.tif"});

    std::ofstream(tmp.file("notes.tif")) << "not a raster\n";
    expect_error<InputError>([&] { load_dem({tmp.file("notes.tif")}); },
                             {"notes.tif", "not a readable raster"});
    expect_error<InputError>([&] { load_dem({tmp.file("missing.tif")}); },
                             {"missing.tif", "not found"});
}

TEST(LoadDem, NanElevationsAreFilledAndCounted) {
    TempDir tmp;
    // A plane z = 1000 + 2 col - 3 row with NaN at (col 2, row 1) and no declared nodata.
    testing::write_raw_geotiff(tmp.file("nan.tif"), 5, 4, {600000, 10, 0, 5200040, 0, -10},
                               "EPSG:32632", [](int c, int r) {
                                   return c == 2 && r == 1
                                              ? std::numeric_limits<double>::quiet_NaN()
                                              : 1000.0 + 2 * c - 3 * r;
                               });
    const Dem dem = load_dem({tmp.file("nan.tif")});
    EXPECT_EQ(dem.filled_voids, 1);
    EXPECT_EQ(dem.filled_holes, 1);
    const std::size_t k = static_cast<std::size_t>(4 - 1 - 1) * 5 + 2;  // j = ny-1-row
    EXPECT_EQ(dem.filled_mask[k], static_cast<std::uint8_t>(CellOrigin::filled_hole));
    EXPECT_NEAR(dem.z[k], 1000.0 + 4 - 3, 1.0);  // interpolated from the plane
    EXPECT_TRUE(all_finite(dem.z));
}

// Filling voids writes no temporary files: GDALFillNodata put two grid-sized GeoTIFFs
// in the working directory (or CPL_TMPDIR), so a run from a folder it cannot write in
// failed with "GDALFillNodata failed on the DEM voids". Here the temporary folder
// GDAL would use does not exist.
TEST(LoadDem, VoidsAreFilledWithoutTemporaryFiles) {
    TempDir tmp;
    testing::write_raw_geotiff(tmp.file("nan.tif"), 5, 4, {600000, 10, 0, 5200040, 0, -10},
                               "EPSG:32632", [](int c, int r) {
                                   return c == 2 && r == 1 ? std::numeric_limits<double>::quiet_NaN()
                                                           : 1000.0 + 2 * c - 3 * r;
                               });
    const std::string missing = tmp.file("no-such-folder");
    const std::string before = CPLGetConfigOption("CPL_TMPDIR", "");
    CPLSetConfigOption("CPL_TMPDIR", missing.c_str());
    Dem dem;
    EXPECT_NO_THROW(dem = load_dem({tmp.file("nan.tif")}));
    CPLSetConfigOption("CPL_TMPDIR", before.empty() ? nullptr : before.c_str());
    EXPECT_EQ(dem.filled_voids, 1);
    EXPECT_TRUE(all_finite(dem.z));
    EXPECT_FALSE(std::filesystem::exists(missing));
}

TEST(LoadDem, UndeclaredVoidMarkersAreRefused) {
    TempDir tmp;
    testing::write_raw_geotiff(
        tmp.file("aster.tif"), 4, 4, {600000, 10, 0, 5200040, 0, -10}, "EPSG:32632",
        [](int c, int r) { return c == 0 && r == 0 ? -9999.0 : 900.0; }, GDT_Int16);
    expect_error<InputError>([&] { load_dem({tmp.file("aster.tif")}); },
                             {"aster.tif", "declares no nodata"});
}

TEST(LoadDem, OptionsAreChecked) {
    const std::string path = testing::avaKot("avaKot_dem.tif");
    DemOptions opts;
    opts.resampling = "bicubic-ish";
    expect_error<ConfigError>([&] { load_dem({path}, opts); }, {"resampling", "bicubic-ish"});
    opts = DemOptions{};
    opts.crs = "EPSG:4326";
    expect_error<ConfigError>([&] { load_dem({path}, opts); }, {"crs", "not a projected CRS"});
    opts.crs = "EPSG:not-a-code";
    expect_error<ConfigError>([&] { load_dem({path}, opts); }, {"crs", "cannot interpret"});
    opts = DemOptions{};
    opts.max_solver_bytes = 1e6;  // 5000 cells at 200 B
    // The DEM that does not fit is the input at fault (exit 3): named, with the estimate.
    expect_error<InputError>([&] { load_dem({path}, opts); },
                             {"avaKot_dem.tif", "cell_size", "GiB", "the default limit"});
    expect_error<ConfigError>([&] { load_dem({}); }, {"no DEM file"});
}

}  // namespace
}  // namespace avalanche::gis
