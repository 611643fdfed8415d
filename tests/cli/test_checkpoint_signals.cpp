// Signals, refusals and numerical faults around checkpoints: SIGTERM writes a
// checkpoint and products marked incomplete (exit 6) that --resume completes; --resume
// refuses, with one line and exit 3, a folder without a checkpoint, a corrupt one,
// inputs that changed, or a checkpoint written by a program built from other sources;
// a NaN writes diagnostic_checkpoint.h5 and no complete product.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "avalanche/io/effective_config.hpp"
#include "checkpoint_test_support.hpp"

namespace avalanche {
namespace {

using test::ChildRun;
using test::ScratchDir;

const char* const kMaps[] = {"max_depth",    "max_velocity",      "max_pressure",
                             "arrival_time", "deposit_thickness", "hazard_class"};

// The small chute on cells fine enough that its time loop lasts about 1.8 s (it stops
// at rest after 3.7 simulated seconds): on 0.1 m cells it lasted 0.47 s, and the
// signal sent 0.4 s after results.h5.part appeared came after the loop on a busy CI
// machine now and then (exit 0 instead of 6).
std::string slow_chute() {
    std::string s = test::kSmallChute;
    s.replace(s.find("cell_size = 0.5"), 15, "cell_size = 0.0625");
    s.replace(s.find("t_end = 0.5"), 11, "t_end = 6.0");
    s.replace(s.find("output_interval = 0.25"), 22, "output_interval = 0.5");
    return s;
}

void expect_one_error_line(const test::ProcessResult& r, const std::string& needle) {
    const auto lines = test::lines_of(r.err);
    ASSERT_EQ(lines.size(), 1u) << r.err;
    EXPECT_EQ(lines[0].rfind("avalanche-hazard: error: ", 0), 0u) << lines[0];
    EXPECT_NE(lines[0].find(needle), std::string::npos) << lines[0];
}

// The small chute run to its end with a checkpoint every 0.1 s into `out` (the last one
// stays); the exit code.
int run_small_chute_with_checkpoints(const ScratchDir& dir, const std::string& out) {
    const std::string file = dir.write("scenario.toml", test::kSmallChute);
    return test::run_binary(dir, "run -q --scenario '" + file + "' --out '" + out +
                                     "' --checkpoint-interval 0.1")
        .exit_code;
}

TEST(CheckpointSignals, SigtermMarksProductsIncompleteAndResumeCompletesThem) {
    ScratchDir dir("ckpt-sigterm");
    const std::string file = dir.write("scenario.toml", slow_chute());
    const std::string ref = dir.file("ref"), out = dir.file("out");
    // No --checkpoint-interval: the signal alone must leave a checkpoint.
    ASSERT_EQ(
        test::run_binary(dir, "run -q --scenario '" + file + "' --out '" + ref + "'").exit_code, 0);
    {
        ChildRun run(dir, {"run", "-q", "--scenario", file, "--out", out}, "term");
        ASSERT_TRUE(run.wait_for_file(out + "/results.h5.part", std::chrono::seconds(60)));
        std::this_thread::sleep_for(std::chrono::milliseconds(400));
        ASSERT_FALSE(run.finished()) << "the run ended before the signal: make the scene longer";
        run.signal(SIGTERM);
        const int status = run.wait();
        ASSERT_TRUE(WIFEXITED(status)) << run.stderr_text();
        EXPECT_EQ(WEXITSTATUS(status), 6) << run.stderr_text();
        EXPECT_NE(run.stderr_text().find("--resume " + out), std::string::npos)
            << run.stderr_text();
    }
    ASSERT_TRUE(std::filesystem::exists(out + "/checkpoint.h5"));
    const auto partial = test::read_json_file(out + "/summary.json");
    EXPECT_EQ(partial["complete"], false);
    EXPECT_EQ(partial["end_reason"], "interrupted");
    EXPECT_LT(partial["simulated_time_s"].get<double>(), 6.0);
    for (const char* m : kMaps) {
        EXPECT_EQ(test::gdal_dataset_metadata(out + "/" + m + ".tif", "AVALANCHE_COMPLETE"), "NO")
            << m;
        EXPECT_EQ(test::gdal_dataset_metadata(out + "/" + m + ".tif", "AVALANCHE_STATUS"),
                  "incomplete")
            << m;
        EXPECT_EQ(test::gdal_dataset_metadata(ref + "/" + m + ".tif", "AVALANCHE_COMPLETE"), "YES")
            << m;
    }
    // The reports say so before anything else; the complete reference run's do not.
    for (const char* report : {"/report.html", "/report.md"}) {
        EXPECT_NE(test::read_text(out + report).find("INCOMPLETE"), std::string::npos) << report;
        EXPECT_EQ(test::read_text(ref + report).find("INCOMPLETE"), std::string::npos) << report;
    }

    const auto r = test::run_binary(dir, "run -q --resume '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::read_json_file(out + "/summary.json")["complete"], true);
    for (const char* report : {"/report.html", "/report.md"})
        EXPECT_EQ(test::read_text(out + report).find("INCOMPLETE"), std::string::npos) << report;
    for (const char* m : kMaps)
        EXPECT_EQ(test::gdal_dataset_metadata(out + "/" + m + ".tif", "AVALANCHE_COMPLETE"), "YES")
            << m;
    test::expect_same_products(ref, out);
}

TEST(CheckpointSignals, ResumeWithoutACheckpointIsAnInputError) {
    ScratchDir dir("ckpt-none");
    std::filesystem::create_directories(dir.file("empty"));
    const auto r = test::run_binary(dir, "run --resume '" + dir.file("empty") + "'");
    EXPECT_EQ(r.exit_code, 3);
    expect_one_error_line(r, dir.file("empty") + "/checkpoint.h5: no checkpoint to resume from");
}

TEST(CheckpointSignals, CorruptOrTruncatedCheckpointIsAnInputError) {
    ScratchDir dir("ckpt-corrupt");
    const std::string out = dir.file("out");
    ASSERT_EQ(run_small_chute_with_checkpoints(dir, out), 0);
    const std::string ckpt = out + "/checkpoint.h5";
    const auto size = std::filesystem::file_size(ckpt);
    std::filesystem::copy_file(ckpt, dir.file("good.h5"));

    std::filesystem::resize_file(ckpt, size / 2);  // a disk that filled up, a copy cut short
    auto r = test::run_binary(dir, "run --resume '" + out + "'");
    EXPECT_EQ(r.exit_code, 3);
    expect_one_error_line(r, ckpt + ": ");

    std::ofstream(ckpt, std::ios::trunc) << "not hdf5 at all";
    r = test::run_binary(dir, "run --resume '" + out + "'");
    EXPECT_EQ(r.exit_code, 3);
    expect_one_error_line(r, ckpt + ": not a readable HDF5 checkpoint");
}

TEST(CheckpointSignals, ResumeRefusesInputsThatChanged) {
    ScratchDir dir("ckpt-changed");
    const std::string dem = dir.file("dem.tif");
    ASSERT_TRUE(test::gdal_translate(test::avaKot("avaKot_dem.tif"), dem, {}));
    const std::string scenario = dir.write(
        "scenario.toml", "[terrain]\ntype = \"dem\"\ndem = \"" + dem +
                             "\"\n[release]\npolygons = \"" + test::avaKot("avaKot_release.gpkg") +
                             "\"\nthickness = 2.0\n[numerics]\ncell_size = 40.0\nt_end = 4.0\n");
    const std::string out = dir.file("out");
    ASSERT_EQ(test::run_binary(dir, "run -q --scenario '" + scenario + "' --out '" + out +
                                        "' --checkpoint-interval 1")
                  .exit_code,
              0);
    // The same file name, terrain raised by 0.1 %: the prepared slopes differ.
    ASSERT_TRUE(test::gdal_translate(test::avaKot("avaKot_dem.tif"), dir.file("raised.tif"),
                                     {"-ot", "Float32", "-scale", "0", "1", "0", "1.001"}));
    std::filesystem::rename(dir.file("raised.tif"), dem);
    const auto r = test::run_binary(dir, "run --resume '" + out + "'");
    EXPECT_EQ(r.exit_code, 3);
    expect_one_error_line(
        r, out + "/checkpoint.h5: the inputs changed since the checkpoint was written");
}

TEST(CheckpointSignals, ResumeRefusesACheckpointOfAProgramBuiltFromOtherSources) {
    ScratchDir dir("ckpt-sources");
    const std::string out = dir.file("out");
    ASSERT_EQ(run_small_chute_with_checkpoints(dir, out), 0);
    const std::string ckpt = out + "/checkpoint.h5";
    // This program resumes its own checkpoint (the run above completed it; resuming a
    // completed run reproduces it): the attribute it wrote is its own hash.
    ASSERT_EQ(test::read_h5_string_attribute(ckpt, "source_hash"), source_hash());
    test::replace_h5_string_attribute(ckpt, "source_hash", "0123456789abcdef");
    const auto r = test::run_binary(dir, "run --resume '" + out + "'");
    EXPECT_EQ(r.exit_code, 3);
    expect_one_error_line(r, ckpt + ": was written by avalanche-hazard " + software_version() +
                                 " built from sources 0123456789abcdef, this program's "
                                 "sources are " +
                                 source_hash());
}

TEST(CheckpointSignals, ResumeTakesNoScenarioFlags) {
    ScratchDir dir("ckpt-flags");
    const auto r = test::run_binary(dir, "run --resume '" + dir.file("x") + "' --cfl 0.3");
    EXPECT_EQ(r.exit_code, 2);
    expect_one_error_line(r, "--resume: takes only --threads");
}

TEST(CheckpointSignals, NumericalFaultWritesADiagnosticCheckpointAndNoCompleteProduct) {
    ScratchDir dir("ckpt-nan");
    const std::string file = dir.write("scenario.toml", test::kSmallChute);
    const std::string out = dir.file("out");
    ::setenv("AVALANCHE_TEST_FAULT_AFTER_STEP", "5", 1);
    const auto r = test::run_binary(dir, "run -q --scenario '" + file + "' --out '" + out + "'");
    ::unsetenv("AVALANCHE_TEST_FAULT_AFTER_STEP");
    EXPECT_EQ(r.exit_code, 5);
    const std::string diag = out + "/diagnostic_checkpoint.h5";
    expect_one_error_line(r, "non-finite value (NaN or Inf) in the state at cell");
    EXPECT_NE(r.err.find(diag), std::string::npos) << r.err;
    for (const char* f : {"summary.json", "results.h5", "max_depth.tif", "hazard_class.tif"})
        EXPECT_FALSE(std::filesystem::exists(out + "/" + f)) << f;

    ASSERT_TRUE(std::filesystem::exists(diag));
    EXPECT_EQ(test::h5_group_attribute(diag, "loop", "steps"), 4.0)
        << "the last good step is the one before";
    const auto good = test::read_h5_dataset(diag, "state/h");
    const auto bad = test::read_h5_dataset(diag, "failing_state/h");
    ASSERT_EQ(good.dims, bad.dims);
    ASSERT_EQ(good.dims.size(), 2u);
    EXPECT_EQ(good.dims[0], 8u + 4u) << "ny + 2 ghost layers";
    EXPECT_EQ(good.dims[1], 20u + 4u) << "nx + 2 ghost layers";
    int bad_cells = 0;
    double volume = 0.0;
    for (hsize_t r2 = 2; r2 < good.dims[0] - 2; ++r2)
        for (hsize_t c = 2; c < good.dims[1] - 2; ++c) {
            const double h = good.values[r2 * good.dims[1] + c];
            EXPECT_TRUE(std::isfinite(h));
            volume += h * 0.25;
            if (!std::isfinite(bad.values[r2 * good.dims[1] + c])) ++bad_cells;
        }
    EXPECT_EQ(bad_cells, 1);
    // The box release: 2 m x 1 m x 0.5 m (bed-normal) = 1 m^3; the last good state holds
    // it, less what has left through the open edges by then (mass balance to round-off).
    const double outflow = test::h5_group_attribute(diag, "loop", "outflow_volume");
    EXPECT_GE(outflow, 0.0);
    EXPECT_LT(outflow, 1e-3);
    EXPECT_NEAR(volume + outflow, 1.0, 1e-12);
}

}  // namespace
}  // namespace avalanche
