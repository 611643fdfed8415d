// summary.json and the effective configuration with its hash.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

#include "avalanche/core/error.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/effective_config.hpp"
#include "avalanche/io/sha256.hpp"
#include "avalanche/io/summary_writer.hpp"
#include "io_test_support.hpp"

namespace avalanche {
namespace {

// The hash the build wrote (cmake/source_hash.cmake) derived again here from the files:
// every .cpp and .hpp under src/ and include/, sorted by path, one line "path sha256"
// each, hashed; a stale generated header (a build that missed a change) fails it.
TEST(SourceHash, IsTheSha256OfTheListingOfTheSourcesThisTestWasBuiltFrom) {
    namespace fs = std::filesystem;
    const fs::path root = AVALANCHE_SOURCE_DIR;
    std::vector<std::string> files;
    for (const char* dir : {"src", "include"})
        for (const auto& e : fs::recursive_directory_iterator(root / dir)) {
            const auto ext = e.path().extension();
            if (e.is_regular_file() && (ext == ".cpp" || ext == ".hpp"))
                files.push_back(e.path().string());
        }
    std::sort(files.begin(), files.end());
    ASSERT_GT(files.size(), 100u);
    std::string listing;
    for (const auto& f : files)
        listing += fs::relative(f, root).string() + " " + sha256_file_hex(f) + "\n";
    EXPECT_EQ(source_hash(), sha256_hex(listing).substr(0, 16));
}

TEST(EffectiveConfig, HoldsEveryParameterAndItsHashFollowsThem) {
    Scenario s;
    s.cell_size = 0.2;
    const auto config = effective_config(s);
    for (const char* section : {"terrain", "release", "material", "numerics", "points", "output"})
        EXPECT_TRUE(config.contains(section)) << section;
    EXPECT_EQ(config["terrain"]["type"], "chute");
    EXPECT_EQ(config["release"]["shape"], "cap");
    EXPECT_EQ(config["numerics"]["cell_size"], 0.2);
    EXPECT_EQ(config["numerics"]["scheme"], "waf");
    EXPECT_EQ(config["material"]["earth_pressure"], "savage-hutter");

    const std::string hash = config_hash(config);
    EXPECT_EQ(hash, config_hash(effective_config(s)));  // deterministic
    Scenario other = s;
    other.material.delta_deg += 1e-9;
    EXPECT_NE(hash, config_hash(effective_config(other)));
    // FNV-1a 64 of the two characters "" (the dump of an empty JSON string): pins the
    // algorithm, so a changed hash function cannot pass unnoticed.
    EXPECT_EQ(config_hash(nlohmann::json("")), "07cc7607b4949e25");
}

// A resumed batch compares this hash (docs/batch.md): the input paths, and nothing else,
// may differ.
TEST(EffectiveConfig, HashWithoutPathsIgnoresTheInputPathsOnly) {
    Scenario s;
    s.terrain = DemTerrainSpec{{"inputs/dem.tif"}, "EPSG:31287"};
    s.release = PolygonReleaseSpec{"inputs/release.gpkg", std::nullopt, "thickness", std::nullopt};
    s.points = PointsSpec{"inputs/points.csv", ""};
    Scenario moved = s;
    moved.terrain = DemTerrainSpec{{"/elsewhere/dem.tif"}, "EPSG:31287"};
    moved.release = PolygonReleaseSpec{"/elsewhere/release.gpkg", std::nullopt, "thickness", std::nullopt};
    moved.points = PointsSpec{"/elsewhere/points.csv", ""};
    const auto config = effective_config(s), config_moved = effective_config(moved);
    EXPECT_NE(config_hash(config), config_hash(config_moved));
    EXPECT_EQ(config_hash_without_paths(config), config_hash_without_paths(config_moved));
    EXPECT_NE(config_hash_without_paths(config), config_hash(config));

    Scenario raster = s, raster_moved = s;
    raster.release = RasterReleaseSpec{"inputs/release.tif"};
    raster_moved.release = RasterReleaseSpec{"release.tif"};
    EXPECT_EQ(config_hash_without_paths(effective_config(raster)),
              config_hash_without_paths(effective_config(raster_moved)));
    EXPECT_NE(config_hash_without_paths(effective_config(raster)), config_hash_without_paths(config));

    // Everything else still counts, the names of the CRS and the thickness field included.
    Scenario other = s;
    other.material.delta_deg += 1e-9;
    EXPECT_NE(config_hash_without_paths(effective_config(other)), config_hash_without_paths(config));
    other = s;
    std::get<DemTerrainSpec>(other.terrain).crs = "EPSG:32632";
    EXPECT_NE(config_hash_without_paths(effective_config(other)), config_hash_without_paths(config));
    other = s;
    std::get<PolygonReleaseSpec>(other.release).thickness_field = "depth";
    EXPECT_NE(config_hash_without_paths(effective_config(other)), config_hash_without_paths(config));
    other = s;
    other.points->crs = "EPSG:4326";
    EXPECT_NE(config_hash_without_paths(effective_config(other)), config_hash_without_paths(config));
    // Two DEM tiles are another configuration than one, whatever their names.
    other = s;
    std::get<DemTerrainSpec>(other.terrain).dem_paths.push_back("inputs/dem2.tif");
    EXPECT_NE(config_hash_without_paths(effective_config(other)), config_hash_without_paths(config));
}

TEST(Summary, HasEveryDocumentedKeyFromTheRunStatistics) {
    SummaryInputs in;
    in.stats.end_reason = EndReason::stopped_kinetic_energy;
    in.stats.simulated_time = 12.5;
    in.stats.steps = 1000;
    in.stats.cell_updates = 2'000'000;
    in.stats.wall_seconds = 2.0;
    in.stats.threads = 2;
    in.stats.released_volume = 10.0;
    in.stats.final_volume = 9.0;
    in.stats.outflow_volume = 1.0;
    in.stats.max_kinetic_energy = 8.0;
    in.stats.final_kinetic_energy = 2e-3;
    in.config = effective_config(Scenario{});
    in.config_hash = config_hash(in.config);
    in.command_line = "avalanche-hazard run --scenario s.toml --out o";
    in.h_min = 2.5e-5;
    const auto j = make_summary(in);
    EXPECT_EQ(j["end_reason"], "stopped_kinetic_energy");
    EXPECT_EQ(j["simulated_time_s"], 12.5);
    EXPECT_EQ(j["steps"], 1000);
    EXPECT_EQ(j["wall_s"], 2.0);
    EXPECT_EQ(j["performance"]["cell_updates"], 2'000'000);
    EXPECT_EQ(j["performance"]["cell_updates_per_s"], 1e6);
    EXPECT_EQ(j["performance"]["threads"], 2);
    EXPECT_EQ(j["volume"]["released_m3"], 10.0);
    EXPECT_EQ(j["volume"]["final_m3"], 9.0);
    EXPECT_EQ(j["volume"]["outflow_m3"], 1.0);
    EXPECT_EQ(j["volume"]["relative_error"], 0.0);
    EXPECT_EQ(j["max_kinetic_energy_m5_per_s2"], 8.0);
    EXPECT_EQ(j["final_kinetic_energy_m5_per_s2"], 2e-3);
    EXPECT_EQ(j["final_kinetic_energy_fraction"], 2e-3 / 8.0);
    EXPECT_EQ(j["parameters"], in.config);
    EXPECT_EQ(j["config_hash"], in.config_hash);
    EXPECT_EQ(j["software_version"], software_version());
    EXPECT_EQ(j["source_hash"], source_hash());
    EXPECT_EQ(j["command_line"], in.command_line);
    EXPECT_EQ(j["h_min_m"], 2.5e-5);
}

TEST(Summary, IsWrittenAtomically) {
    test::ScratchDir dir("summary");
    const std::string path = dir.file("summary.json");
    SummaryInputs in;
    write_summary(path, in);
    EXPECT_FALSE(std::filesystem::exists(path + ".part"));
    std::ifstream f(path);
    const auto j = nlohmann::json::parse(f);
    EXPECT_EQ(j["end_reason"], "end_time");
}

TEST(AtomicFile, UnwritableFolderIsAnOutputErrorNamingThePath) {
    try {
        write_file_atomically("/nonexistent-folder/summary.json", "{}");
        FAIL() << "expected OutputError";
    } catch (const OutputError& e) {
        EXPECT_EQ(e.code(), ExitCode::output);
        EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/summary.json"),
                  std::string::npos);
    }
}

}  // namespace
}  // namespace avalanche
