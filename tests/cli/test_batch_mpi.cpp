// A batch under `mpirun -n 2` writes what one process writes (docs/batch.md, "Many
// machines"): the same comparison.csv apart from the wall-clock column, the same envelope
// and frequency maps, the same calibration; and each rank really ran its share. Also the
// log lines of concurrent scenarios: each names its scenario, and the right one.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>

#include "avalanche/gis/raster_reader.hpp"
#include "batch_test_support.hpp"

namespace avalanche {
namespace {

namespace fs = std::filesystem;

// The whole 60 m x 40 m chute as the "observed" deposit: Jaccard = reached cells / all
// cells = affected_area_m2 / (60 m * 40 m) (the chute's cell area is the bed area).
const char* kWholeChute =
    R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
    R"("geometry":{"type":"Polygon","coordinates":[[[0,0],[60,0],[60,40],[0,40],[0,0]]]}}]})";

// A CSV row without its last cell (wall_s, the only column allowed to differ).
std::vector<std::vector<std::string>> without_wall_time(std::vector<std::vector<std::string>> csv) {
    for (auto& row : csv) row.pop_back();
    return csv;
}

std::string batch_args(const std::string& base, const std::string& observed,
                       const std::string& out) {
    return "batch --scenario '" + base + "' --sweep delta=20,25,30 --observed '" + observed +
           "' --out '" + out + "'";
}

TEST(BatchMpi, TwoRanksWriteWhatOneProcessWrites) {
#ifndef AVALANCHE_MPIEXEC
    GTEST_SKIP() << "built without MPI (AVALANCHE_WITH_MPI=OFF)";
#else
    test::ScratchDir dir("batch-mpi");
    const auto base = dir.write("base.toml", test::kCoarseParametricChute);
    const auto observed = dir.write("whole.geojson", kWholeChute);
    const std::string single = dir.file("single"), ranks = dir.file("ranks");
    const auto one = test::run_binary(dir, batch_args(base, observed, single) + " --parallel 1");
    ASSERT_EQ(one.exit_code, 0) << one.err;

    // CI runs as root, which Open MPI refuses unless told; 2 ranks may exceed the slots a
    // small machine offers, hence oversubscription; containers often forbid the
    // cross-process memory copy Open MPI's shared-memory transport tries first, hence
    // single_copy_mechanism=none. One OpenMP thread per rank (as ctest sets).
    const auto two = test::run_command(
        dir, std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                         "OMPI_MCA_rmaps_base_oversubscribe=1 "
                         "OMPI_MCA_btl_vader_single_copy_mechanism=none OMP_NUM_THREADS=1 '") +
                 AVALANCHE_MPIEXEC + "' -n 2 '" AVALANCHE_BINARY "' " +
                 batch_args(base, observed, ranks) + " --parallel 1");
    ASSERT_EQ(two.exit_code, 0) << two.err;
    // Both ranks worked: 3 scenarios round-robin are 2 on rank 0 and 1 on rank 1.
    EXPECT_NE(two.err.find("MPI rank 0 of 2: 2 scenario(s)"), std::string::npos) << two.err;
    EXPECT_NE(two.err.find("MPI rank 1 of 2: 1 scenario(s)"), std::string::npos) << two.err;
    EXPECT_EQ(one.err.find("MPI rank"), std::string::npos) << one.err;

    const auto a = test::read_csv(single + "/comparison.csv");
    const auto b = test::read_csv(ranks + "/comparison.csv");
    ASSERT_EQ(a.size(), 4u);
    EXPECT_EQ(a[0].back(), "wall_s");
    EXPECT_EQ(without_wall_time(a), without_wall_time(b));
    for (const char* map :
         {"impact_frequency.tif", "envelope_max_depth.tif", "envelope_max_velocity.tif",
          "envelope_max_pressure.tif", "envelope_min_arrival_time.tif"}) {
        const auto x = gis::read_geotiff(single + "/" + map);
        const auto y = gis::read_geotiff(ranks + "/" + map);
        EXPECT_EQ(x.values, y.values) << map;
        EXPECT_FALSE(x.values.empty()) << map;
    }
    EXPECT_EQ(test::read_json(single + "/calibration.json"),
              test::read_json(ranks + "/calibration.json"));
    const auto manifest = test::read_json(ranks + "/manifest.json");
    ASSERT_EQ(manifest["scenarios"].size(), 3u);
    for (const auto& s : manifest["scenarios"]) EXPECT_TRUE(s["complete"].get<bool>());

    // The calibration against the whole chute, derived from each summary's affected area.
    const auto jaccard = std::find(a[0].begin(), a[0].end(), "jaccard") - a[0].begin();
    const auto area = std::find(a[0].begin(), a[0].end(), "affected_area_m2") - a[0].begin();
    ASSERT_LT(static_cast<std::size_t>(jaccard), a[0].size());
    for (std::size_t r = 1; r < a.size(); ++r)
        EXPECT_NEAR(std::stod(a[r][jaccard]), std::stod(a[r][area]) / (60.0 * 40.0), 1e-12);
#endif
}

TEST(BatchLog, EveryLineOfAScenarioNamesItsScenario) {
    test::ScratchDir dir("batch-log");
    const auto base = dir.write("base.toml", test::kCoarseParametricChute);
    const std::string out = dir.file("out");
    // Two scenarios on two threads at once: their lines interleave.
    const auto r =
        test::run_binary(dir, "batch --scenario '" + base +
                                  "' --sweep delta=25,30 --parallel 2 --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // The scene line of each scenario carries its configuration hash: the tag in front
    // of it must name the scenario whose summary.json has that hash.
    std::map<std::string, std::string> hash_of;
    for (const char* id : {"delta=25", "delta=30"})
        hash_of[id] = test::read_json(out + "/" + id + "/summary.json")["config_hash"];
    const std::regex tagged(R"(^info: \[(delta=[0-9]+)\] (.*)$)");
    const std::regex scene_line(R"(chute 60 x 40 m.* config ([0-9a-f]+)$)");
    std::map<std::string, int> lines_of;
    int scene_lines = 0;
    for (const auto& line : test::lines_of(r.err)) {
        // The lines execute_scene writes for a scenario (scene, end, volume, runout).
        const bool scenario_line = line.find("chute 60 x 40 m") != std::string::npos ||
                                   line.find("ended (") != std::string::npos ||
                                   line.find("volume: released") != std::string::npos ||
                                   line.find("travel angle") != std::string::npos;
        std::smatch m;
        if (!std::regex_match(line, m, tagged)) {
            EXPECT_FALSE(scenario_line) << "untagged: " << line;
            continue;
        }
        const std::string id = m[1], text = m[2];
        ++lines_of[id];
        std::smatch h;
        if (std::regex_search(text, h, scene_line)) {
            EXPECT_EQ(h[1].str(), hash_of[id]) << line;
            ++scene_lines;
        }
    }
    EXPECT_EQ(scene_lines, 2);
    EXPECT_GE(lines_of["delta=25"], 4) << r.err;
    EXPECT_GE(lines_of["delta=30"], 4) << r.err;
}

}  // namespace
}  // namespace avalanche
