// run_cli in-process: flags override the scenario file, and summary.json / results.h5
// carry the effective values and an exact mass balance.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "avalanche/app/cli.hpp"
#include "cli_test_support.hpp"

namespace avalanche {
namespace {

nlohmann::json read_json(const std::string& path) {
    std::ifstream f(path);
    return nlohmann::json::parse(f);
}

std::vector<double> read_time(const std::string& file) {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t ds = H5Dopen2(f, "time", H5P_DEFAULT);
    const hid_t space = H5Dget_space(ds);
    std::vector<double> t(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, t.data());
    H5Sclose(space);
    H5Dclose(ds);
    H5Fclose(f);
    return t;
}

TEST(RunInProcess, SummaryHasEveryKeyAndAnExactMassBalance) {
    test::ScratchDir dir("summary");
    const std::string scenario = dir.write("scenario.toml", test::kSmallChute);
    const std::string out = dir.file("out");
    const auto started = std::chrono::steady_clock::now();
    ASSERT_EQ(run_cli({"avalanche-hazard", "run", "--scenario", scenario, "--out", out, "--quiet"}),
              0);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const auto s = read_json(out + "/summary.json");
    // The wall time of each phase, in the order they ran; the solver's phase holds the
    // time loop (wall_s), and all of them fit in the command's own time.
    const auto& phases = s["performance"]["phases_s"];
    double sum = 0.0;
    for (const char* phase : {"prepare", "setup", "simulate", "results", "products", "report"}) {
        ASSERT_TRUE(phases.contains(phase)) << phase;
        EXPECT_GE(phases[phase].get<double>(), 0.0) << phase;
        sum += phases[phase].get<double>();
    }
    EXPECT_EQ(phases.size(), 7u);  // the six and the total
    EXPECT_NEAR(phases["total"].get<double>(), sum, 1e-12 * sum);
    EXPECT_LE(phases["total"].get<double>(), elapsed);
    EXPECT_GE(phases["simulate"].get<double>(), s["wall_s"].get<double>());
    EXPECT_GT(phases["products"].get<double>(), 0.0);
    for (const char* key : {"end_reason", "simulated_time_s", "steps", "wall_s", "performance",
                            "volume", "parameters", "config_hash", "software_version",
                            "source_hash", "command_line", "h_min_m"})
        EXPECT_TRUE(s.contains(key)) << key;
    for (const char* key : {"cell_updates", "cell_updates_per_s", "threads"})
        EXPECT_TRUE(s["performance"].contains(key)) << key;
    EXPECT_EQ(s["end_reason"], "end_time");
    EXPECT_DOUBLE_EQ(s["simulated_time_s"].get<double>(), 0.5);
    EXPECT_GT(s["steps"].get<int>(), 0);
    EXPECT_GT(s["performance"]["cell_updates"].get<double>(), 0.0);
    EXPECT_GE(s["performance"]["threads"].get<int>(), 1);
    // Box 2 m x 1 m x 0.5 m, cell edges aligned: exactly 1 m^3.
    EXPECT_DOUBLE_EQ(s["volume"]["released_m3"].get<double>(), 1.0);
    EXPECT_GE(s["volume"]["outflow_m3"].get<double>(), 0.0);  // the thin front may reach an edge
    EXPECT_LT(std::abs(s["volume"]["relative_error"].get<double>()), 1e-12);
    EXPECT_NE(s["command_line"].get<std::string>().find("--scenario"), std::string::npos);
    EXPECT_EQ(s["config_hash"].get<std::string>().size(), 16u);
    EXPECT_GT(s["h_min_m"].get<double>(), 0.0);

    const auto t = read_time(out + "/results.h5");
    EXPECT_EQ(t, (std::vector<double>{0.0, 0.25, 0.5}));
}

TEST(RunInProcess, FlagsOverrideTheScenarioFile) {
    test::ScratchDir dir("overrides");
    const std::string scenario = dir.write("scenario.toml", test::kSmallChute);
    const std::string out = dir.file("out");
    ASSERT_EQ(run_cli({"avalanche-hazard",
                       "run",
                       "--scenario",
                       scenario,
                       "--out",
                       out,
                       "--quiet",
                       "--t-end",
                       "0.3",
                       "--output-interval",
                       "0.1",
                       "--phi",
                       "30",
                       "--delta",
                       "18",
                       "--scheme",
                       "godunov",
                       "--limiter",
                       "minmod",
                       "--cfl",
                       "0.4",
                       "--stop-ke-fraction",
                       "0.001",
                       "--rest-faces",
                       "--density",
                       "1500",
                       "--earth-pressure",
                       "isotropic",
                       "--thickness",
                       "0.25",
                       "--threads",
                       "1"}),
              0);
    const auto s = read_json(out + "/summary.json");
    const auto& p = s["parameters"];
    EXPECT_EQ(p["numerics"]["t_end"], 0.3);
    EXPECT_EQ(p["numerics"]["output_interval"], 0.1);
    EXPECT_EQ(p["numerics"]["scheme"], "godunov");
    EXPECT_EQ(p["numerics"]["limiter"], "minmod");
    EXPECT_EQ(p["numerics"]["cfl"], 0.4);
    EXPECT_EQ(p["numerics"]["stop_ke_fraction"], 0.001);
    EXPECT_EQ(p["numerics"]["rest_faces"], true);
    EXPECT_EQ(p["numerics"]["cell_size"], 0.5);  // from the file
    EXPECT_EQ(p["material"]["phi_deg"], 30.0);
    EXPECT_EQ(p["material"]["delta_deg"], 18.0);
    EXPECT_EQ(p["material"]["density"], 1500.0);
    EXPECT_EQ(p["material"]["earth_pressure"], "isotropic");
    EXPECT_EQ(p["release"]["thickness"], 0.25);
    EXPECT_EQ(s["performance"]["threads"], 1);
    EXPECT_DOUBLE_EQ(s["volume"]["released_m3"].get<double>(), 0.5);
    EXPECT_DOUBLE_EQ(s["simulated_time_s"].get<double>(), 0.3);
    const auto t = read_time(out + "/results.h5");
    ASSERT_EQ(t.size(), 4u);
    EXPECT_DOUBLE_EQ(t.back(), 0.3);
}

TEST(RunInProcess, ErrorsReturnTheirExitCodeAndDebugLetsThemEscape) {
    test::ScratchDir dir("debug");
    const std::string scenario = dir.write("scenario.toml", test::kSmallChute);
    const std::vector<std::string> args{
        "avalanche-hazard", "run",   "--scenario", scenario, "--out",
        dir.file("out"),    "--cfl", "0.7"};
    testing::internal::CaptureStderr();
    EXPECT_EQ(run_cli(args), 2);
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(err,
              "avalanche-hazard: error: --cfl: expected a Courant number in (0, 0.5] (Wang & Li "
              "2017 eq. 11), got 0.700000\n");
    auto debug_args = args;
    debug_args.push_back("--debug");
    EXPECT_THROW(run_cli(debug_args), std::runtime_error);
}

// --rest-faces is a switch with a negation, so a run can turn off what its scenario file
// turns on; --rest-faces=true|false also, any other value is refused before anything runs.
TEST(RunInProcess, RestFacesSwitchTurnsTheFilesSettingOnOrOff) {
    test::ScratchDir dir("rest-faces-switch");
    std::string toml = test::kSmallChute;
    toml.replace(toml.find("[numerics]\n"), 11, "[numerics]\nrest_faces = true\n");
    const std::string scenario = dir.write("scenario.toml", toml);
    const auto run_with = [&](const std::string& flag, const std::string& name) {
        const std::string out = dir.file(name);
        std::vector<std::string> args{
            "avalanche-hazard", "run",     "--scenario", scenario,    "--out", out,
            "--quiet",          "--t-end", "0.05",       "--threads", "1"};
        if (!flag.empty()) args.push_back(flag);
        EXPECT_EQ(run_cli(args), 0) << flag;
        return read_json(out + "/summary.json")["parameters"]["numerics"]["rest_faces"];
    };
    EXPECT_EQ(run_with("", "file"), true);
    EXPECT_EQ(run_with("--no-rest-faces", "off"), false);
    EXPECT_EQ(run_with("--rest-faces=false", "off_value"), false);
    EXPECT_EQ(run_with("--rest-faces=true", "on_value"), true);

    testing::internal::CaptureStderr();
    EXPECT_EQ(run_cli({"avalanche-hazard", "run", "--scenario", scenario, "--out", dir.file("bad"),
                       "--rest-faces=yes"}),
              2);
    EXPECT_EQ(testing::internal::GetCapturedStderr(),
              "avalanche-hazard: error: --rest-faces: expected true or false, got \"yes\"\n");
    EXPECT_FALSE(std::filesystem::exists(dir.file("bad")));
}

}  // namespace
}  // namespace avalanche
