// The products (six maps with their styles and quick-looks, the computational DEM) are
// written by as many threads as the run has (products.cpp): the files, and their order
// in summary.json, are those of one thread, byte for byte.
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

}  // namespace
}  // namespace avalanche
