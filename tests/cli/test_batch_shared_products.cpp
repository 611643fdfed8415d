// A batch's scenarios of one scene share the products that depend on the scene alone
// (shared_scene_products.hpp, docs/batch.md "Outputs in DIR"): dem.tif is one file
// linked into every scenario's folder, and the quick-looks drawn over the shared
// hillshade are byte for byte those of the same scenario run alone.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "batch_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche {
namespace {

namespace fs = std::filesystem;

TEST(BatchSharedProducts, ScenariosOfOneSceneLinkOneDemAndDrawTheQuicklooksOfARunAlone) {
    test::ScratchDir dir("batch-shared");
    const std::string scene = "--dem '" + test::avaKot("avaKot_dem.tif") + "' --release '" +
                              test::avaKot("avaKot_release.gpkg") +
                              "' --cell-size 40 --t-end 10 --output-interval 5";
    const std::string batch = dir.file("batch"), single = dir.file("single");
    auto r = test::run_binary(dir, "batch " + scene + " --thickness-field thickness " +
                                       "--sweep delta=25,30 --out '" + batch + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Alone, on the one thread each of the batch's two scenarios had on two cores.
    r = test::run_binary(dir, "run " + scene + " --thickness-field thickness --delta 30 " +
                                  "--threads 1 --out '" + single + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;

    const std::string dem25 = batch + "/delta=25/dem.tif", dem30 = batch + "/delta=30/dem.tif";
    EXPECT_TRUE(fs::equivalent(dem25, dem30));
    EXPECT_EQ(fs::hard_link_count(dem30), 2u);
    EXPECT_EQ(test::read_text(dem30), test::read_text(single + "/dem.tif"));
    for (const char* png : {"max_depth.png", "arrival_time.png", "hazard_class.png"})
        EXPECT_EQ(test::read_text(batch + "/delta=30/" + png), test::read_text(single + "/" + png))
            << png;

    // A thickness sweep prepares one scene per value: each writes its own DEM (the same
    // terrain, so the same bytes).
    const std::string thick = dir.file("thickness");
    r = test::run_binary(dir, "batch " + scene + " --sweep thickness=1,2 --out '" + thick + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(fs::equivalent(thick + "/thickness=1/dem.tif", thick + "/thickness=2/dem.tif"));
    EXPECT_EQ(test::read_text(thick + "/thickness=1/dem.tif"),
              test::read_text(thick + "/thickness=2/dem.tif"));
    EXPECT_EQ(test::read_text(thick + "/thickness=2/dem.tif"), test::read_text(dem30));
}

}  // namespace
}  // namespace avalanche
