// The products (six maps with their styles and quick-looks, the computational DEM) are
// written by as many threads as the run has (products.cpp): the files, and their order
// in summary.json, are those of one thread, byte for byte.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

TEST(ProductsThreads, FilesAreThoseOfOneThreadByteForByte) {
    test::ScratchDir dir("products-threads");
    const auto run = [&](int threads) {
        const std::string out = dir.file("t" + std::to_string(threads));
        const test::ProcessResult r = test::run_binary(
            dir, "run --dem '" + test::avaKot("avaKot_dem.tif") + "' --release '" +
                     test::avaKot("avaKot_release.gpkg") +
                     "' --thickness 2 --cell-size 20 --t-end 20 --output-interval 10 --quiet --threads " +
                     std::to_string(threads) + " --out '" + out + "'");
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return out;
    };
    const std::string one = run(1), three = run(3);
    const auto a = test::read_json_file(one + "/summary.json"), b = test::read_json_file(three + "/summary.json");
    EXPECT_EQ(a["performance"]["threads"], 1);
    EXPECT_EQ(b["performance"]["threads"], 3);
    ASSERT_EQ(a["products"], b["products"]);
    std::size_t compared = 0;
    for (const auto& name : a["products"]) {
        const std::string file = name.get<std::string>();
        const std::string ext = file.substr(file.rfind('.'));
        if (ext != ".tif" && ext != ".png" && ext != ".qml") continue;
        const std::string fa = test::read_text(one + "/" + file), fb = test::read_text(three + "/" + file);
        EXPECT_FALSE(fa.empty()) << file;
        EXPECT_TRUE(fa == fb) << file << " differs";
        ++compared;
    }
    EXPECT_EQ(compared, 19u);  // 6 x (tif, qml, png) and dem.tif
}

// DEFLATE's predictor where it pays (docs/gis.md): the DEM with the floating-point one,
// the hazard maps (nodata outside the affected area) without.
TEST(ProductsThreads, DemWithPredictorMapsWithout) {
    test::ScratchDir dir("products-predictor");
    const std::string out = dir.file("run");
    const test::ProcessResult r = test::run_binary(
        dir, "run --dem '" + test::avaKot("avaKot_dem.tif") + "' --release '" + test::avaKot("avaKot_release.gpkg") +
                 "' --thickness 2 --cell-size 20 --t-end 10 --quiet --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    GDALAllRegister();
    // The PREDICTOR item of the file's image structure; empty without one.
    const auto predictor = [&](const std::string& file) {
        std::string value;
        GDALDataset* ds = GDALDataset::Open((out + "/" + file).c_str(), GDAL_OF_RASTER);
        EXPECT_NE(ds, nullptr) << file;
        if (ds == nullptr) return value;
        if (const char* p = ds->GetMetadataItem("PREDICTOR", "IMAGE_STRUCTURE")) value.assign(p);
        GDALClose(ds);
        return value;
    };
    EXPECT_EQ(predictor("dem.tif"), "3") << "the floating-point predictor";
    for (const char* map : {"max_depth.tif", "max_velocity.tif", "max_pressure.tif", "arrival_time.tif",
                            "deposit_thickness.tif", "hazard_class.tif"})
        EXPECT_EQ(predictor(map), "") << map << " has a predictor";
}

}  // namespace
}  // namespace avalanche
