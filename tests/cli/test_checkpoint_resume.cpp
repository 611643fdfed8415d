// The hard requirement of checkpoints: a run killed with SIGKILL at an arbitrary moment
// after its first checkpoint, then resumed with --resume, writes products identical bit
// for bit to those of an uninterrupted run (same thread count), for the chute frame and
// for a DEM scene with monitoring points and sink cells.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "checkpoint_test_support.hpp"

namespace avalanche {
namespace {

using test::ChildRun;
using test::ScratchDir;

// The small chute of cli_test_support.hpp at 0.1 m cells for 4 s: a few thousand
// cells, about two thousand steps, one to a few seconds of wall time.
std::string slow_chute() {
    std::string s = test::kSmallChute;
    s.replace(s.find("cell_size = 0.5"), 15, "cell_size = 0.1");
    s.replace(s.find("t_end = 0.5"), 11, "t_end = 4.0");
    s.replace(s.find("output_interval = 0.25"), 22, "output_interval = 0.5");
    return s;
}

// avaKot at 20 m cells with its monitoring points: the DEM frame, sinks outside the
// data footprint, the monitoring observer.
std::string dem_scene() {
    return "[terrain]\ntype = \"dem\"\ndem = \"" + test::avaKot("avaKot_dem.tif") +
           "\"\n[release]\npolygons = \"" + test::avaKot("avaKot_release.gpkg") +
           "\"\nthickness = 2.0\n[points]\nfile = \"" + test::avaKot("avaKot_points.gpkg") +
           "\"\n[numerics]\ncell_size = 20.0\nt_end = 60.0\noutput_interval = 10.0\n";
}

// Runs `scenario` uninterrupted into ref/, then again into killed/ with SIGKILL
// `delay` after its first checkpoint, resumes killed/ and compares every product.
void kill_resume_and_compare(const ScratchDir& dir, const std::string& scenario,
                             const std::string& interval, std::chrono::milliseconds delay) {
    const std::string file = dir.write("scenario.toml", scenario);
    const std::string ref = dir.file("ref"), killed = dir.file("killed");
    const std::vector<std::string> base{"run",   "-q", "--scenario", file, "--checkpoint-interval",
                                        interval};

    auto with_out = [&](const std::string& out) {
        auto args = base;
        args.insert(args.end(), {"--out", out});
        return args;
    };
    {
        ChildRun run(dir, with_out(ref), "ref");
        const int status = run.wait();
        ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << run.stderr_text();
    }
    {
        ChildRun run(dir, with_out(killed), "killed");
        ASSERT_TRUE(run.wait_for_file(killed + "/checkpoint.h5", std::chrono::seconds(120)))
            << run.stderr_text();
        std::this_thread::sleep_for(delay);
        ASSERT_FALSE(run.finished()) << "the run ended before the kill: make the scene longer";
        run.signal(SIGKILL);
        const int status = run.wait();
        ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    }
    // Killed mid-run: nothing says "complete", and the checkpoint is not at the end.
    EXPECT_FALSE(std::filesystem::exists(killed + "/summary.json"));
    EXPECT_FALSE(std::filesystem::exists(killed + "/results.h5"));
    const double t_checkpoint = test::h5_group_attribute(killed + "/checkpoint.h5", "loop", "t");
    const double t_end =
        test::read_h5_double_attribute(ref + "/results.h5", "simulated_time").at(0);
    EXPECT_GT(t_checkpoint, 0.0);
    EXPECT_LT(t_checkpoint, t_end);

    ChildRun resumed(dir, {"run", "-q", "--resume", killed}, "resumed");
    const int status = resumed.wait();
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << resumed.stderr_text();
    test::expect_same_products(ref, killed);
    EXPECT_EQ(test::read_json_file(killed + "/summary.json")["complete"], true);
}

TEST(CheckpointResume, ChuteKilledWithSigkillResumesBitForBit) {
    ScratchDir dir("ckpt-kill-chute");
    kill_resume_and_compare(dir, slow_chute(), "0.25", std::chrono::milliseconds(250));
}

TEST(CheckpointResume, DemSceneKilledWithSigkillResumesBitForBit) {
    ScratchDir dir("ckpt-kill-dem");
    kill_resume_and_compare(dir, dem_scene(), "4", std::chrono::milliseconds(200));
}

// Resuming a folder whose run had already completed (killed after the end, or by a
// user) recomputes from the last checkpoint and writes the same products again.
TEST(CheckpointResume, ResumingACompletedRunReproducesIt) {
    ScratchDir dir("ckpt-complete");
    const std::string file = dir.write("scenario.toml", test::kSmallChute);
    const std::string a = dir.file("a"), b = dir.file("b");
    ASSERT_EQ(test::run_binary(dir, "run -q --scenario '" + file + "' --out '" + a +
                                        "' --checkpoint-interval 0.2")
                  .exit_code,
              0);
    std::filesystem::copy(a, b);
    for (const char* f : {"summary.json", "results.h5", "max_depth.tif"})
        std::filesystem::remove(b + "/" + f);
    const auto r = test::run_binary(dir, "run -q --resume '" + b + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    test::expect_same_products(a, b);
}

}  // namespace
}  // namespace avalanche
