// `avalanche-hazard run`: scenario (file < flags) -> prepared scene -> simulation ->
// DIR/results.h5 + DIR/summary.json.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <utility>

#include "avalanche/app/phase_times.hpp"
#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/app/progress_bar.hpp"
#include "avalanche/app/scenario_overrides.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/io/checkpoint_file.hpp"
#include "avalanche/io/effective_config.hpp"
#include "commands.hpp"
#include "interrupt.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace avalanche::detail {

namespace {

// The progress callback: a GDAL-style bar when stderr is a terminal, and the signal check.
std::function<bool(double)> make_progress(bool show_bar) {
    auto bar = show_bar ? std::make_shared<TextProgressBar>(std::cerr) : nullptr;
    return [bar](double fraction) {
        if (bar) bar->update(fraction);
        return !InterruptGuard::requested();
    };
}

// Options of `run` that are not scenario values.
struct CheckpointArguments {
    double interval = 0.0;  // --checkpoint-interval (s)
    std::string resume;     // --resume DIR
};

// A prepared scene and the wall time its preparation took (the summary's "prepare" phase).
struct TimedScene {
    PreparedScene scene;
    double seconds = 0.0;
};

TimedScene prepare_timed(const Scenario& scenario) {
    PhaseTimes clock;
    PreparedScene scene = prepare_scene(scenario);
    clock.lap("prepare");
    return {std::move(scene), clock.total()};
}

// Runs the scene into `out` and turns an interrupted run into exit code 6.
int run_scene(TimedScene&& prepared, const Scenario& scenario, const std::string& out,
              const GlobalOptions& global, double checkpoint_interval,
              const CheckpointContents* resume) {
    InterruptGuard interrupt;
    RunOptions options;
    options.prepare_seconds = prepared.seconds;
    options.out_dir = out;
    options.command_line = global.command_line;
    options.progress = make_progress(!global.quiet && ::isatty(::fileno(stderr)));
    options.checkpoint_interval = checkpoint_interval;
    options.resume = resume;
    const RunOutcome outcome = execute_scene(std::move(prepared.scene), scenario, options);
    if (!global.quiet) {
        const std::string dir = std::filesystem::path(outcome.summary_path).parent_path().string();
        std::cout << "maps: " << dir
                  << "/{max_depth,max_velocity,max_pressure,arrival_time,deposit_thickness,"
                     "hazard_class}.tif (open in QGIS; styles beside them)\nreport: "
                  << dir << "/report.html (the planner's report, opens offline; also report.md)"
                  << "\nresults: " << outcome.results_path << "\nsummary: " << outcome.summary_path
                  << "\n";
    }
    if (outcome.stats.end_reason == EndReason::interrupted)
        throw Error(ExitCode::interrupted,
                    "interrupted at t = " + std::to_string(outcome.stats.simulated_time) +
                        " s; the results so far are in " + out +
                        " (marked incomplete); continue with " + "avalanche-hazard run --resume " +
                        out);
    return 0;
}

void set_threads(int threads) {
    if (threads < 0) throw ConfigError("--threads", "expected a number of threads >= 1");
#ifdef _OPENMP
    if (threads > 0) omp_set_num_threads(threads);
#endif
}

int execute_new_run(const RunArguments& args, const GlobalOptions& global,
                    double checkpoint_interval) {
    if (args.out.empty())
        throw ConfigError("--out", "required: the output folder (or --resume DIR)");
    if (!(checkpoint_interval >= 0.0) || !std::isfinite(checkpoint_interval))
        throw ConfigError("--checkpoint-interval",
                          "expected a positive number of simulated seconds");
    const Scenario scenario = assemble_scenario(args.scenario, args.overrides);
    spdlog::debug("effective configuration: {}", effective_config(scenario).dump());
    set_threads(args.threads);
    prepare_output_folder(args.out, args.overwrite);
    if (args.overwrite) remove_previous_run(args.out);
    return run_scene(prepare_timed(scenario), scenario, args.out, global, checkpoint_interval,
                     nullptr);
}

// Changes the working directory for the life of the guard: a resumed run reads its
// inputs from the paths recorded in the checkpoint, relative to where the run started,
// and must record the very same paths in its outputs.
class WorkingDirectory {
  public:
    WorkingDirectory(const std::string& dir, const std::string& checkpoint)
        : old_(std::filesystem::current_path()) {
        std::error_code ec;
        std::filesystem::current_path(dir, ec);
        if (ec)
            throw InputError(checkpoint, "the run started in " + dir + ", which is gone (" +
                                             ec.message() +
                                             "); its relative input paths cannot be found");
    }
    ~WorkingDirectory() {
        std::error_code ec;
        std::filesystem::current_path(old_, ec);
    }
    WorkingDirectory(const WorkingDirectory&) = delete;
    WorkingDirectory& operator=(const WorkingDirectory&) = delete;

  private:
    std::filesystem::path old_;
};

int execute_resume(const std::string& dir, int threads, const GlobalOptions& global) {
    const std::string out = std::filesystem::absolute(dir).lexically_normal().string();
    const CheckpointContents checkpoint =
        read_checkpoint((std::filesystem::path(out) / "checkpoint.h5").string());
    WorkingDirectory cd(checkpoint.info.working_dir, checkpoint.path);
    Scenario scenario;
    try {
        scenario = scenario_from_config(checkpoint.info.config, checkpoint.path);
    } catch (const ConfigError& e) {
        throw InputError(checkpoint.path,
                         std::string("the recorded configuration is invalid: ") + e.what());
    }
    if (config_hash(effective_config(scenario)) != checkpoint.info.config_hash)
        throw InputError(checkpoint.path, "the recorded configuration does not match its hash " +
                                              checkpoint.info.config_hash +
                                              " (corrupt checkpoint?)");
    // The version is the same for every commit; the source hash tells two builds apart.
    if (checkpoint.info.source_hash != source_hash())
        throw InputError(checkpoint.path,
                         "was written by avalanche-hazard " + checkpoint.info.software_version +
                             " built from sources " + checkpoint.info.source_hash +
                             ", this program's sources are " + source_hash() +
                             "; resuming would mix two solvers in one run: start it "
                             "again with --overwrite");
    set_threads(threads > 0 ? threads : checkpoint.info.threads);
    return run_scene(prepare_timed(scenario), scenario, out, global,
                     checkpoint.info.checkpoint_interval, &checkpoint);
}

}  // namespace

int execute_run(const RunArguments& args, const GlobalOptions& global) {
    return execute_new_run(args, global, 0.0);
}

Command add_run_command(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<RunArguments>();
    auto checkpoints = std::make_shared<CheckpointArguments>();
    CLI::App* cmd =
        app.add_subcommand("run", "Simulate a scenario and write results.h5 and summary.json");
    cmd->fallthrough();  // --quiet, --verbose, --debug may follow the subcommand
    cmd->add_option_function<std::string>(
        "--scenario", [args](const std::string& v) { args->scenario = v; },
        "Scenario file (TOML); its paths are relative to its folder");
    cmd->add_option("--out", args->out,
                    "Output folder (created if missing); required unless --resume");
    cmd->add_flag("--overwrite", args->overwrite, "Replace results already in the output folder");
    cmd->add_option("--threads", args->threads, "OpenMP threads (default: all cores)")
        ->check(CLI::PositiveNumber);
    add_scenario_flags(*cmd, args->overrides);
    cmd->add_option("--checkpoint-interval", checkpoints->interval,
                    "Write DIR/checkpoint.h5 every S simulated seconds (0: only when interrupted)")
        ->default_str("0")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--resume", checkpoints->resume,
                    "Continue the run in this output folder from its checkpoint.h5, with the "
                    "parameters recorded there (only --threads may be given with it)");
    // clang-format off
    cmd->footer(
        "Examples:\n"
        "  avalanche-hazard run --scenario scenarios/parametric_chute/scenario.toml --out out/chute\n"
        "  avalanche-hazard run --scenario scenarios/koch1994/scenario.toml --out out/koch \\\n"
        "      --delta 35 --scheme godunov\n"
        "  avalanche-hazard run --dem area.tif --release release.gpkg --thickness 1.5 --out out/area\n"
        "  avalanche-hazard run --scenario s.toml --out out/long --checkpoint-interval 10\n"
        "  avalanche-hazard run --resume out/long      (after a crash, kill or Ctrl-C)\n"
        "Exit codes: 0 ok, 2 bad flag or scenario value, 3 unreadable input, 4 output folder\n"
        "problem, 5 numerical failure, 6 interrupted, 70 internal error (docs/cli.md).");
    // clang-format on
    return [args, checkpoints, cmd, &global] {
        if (checkpoints->resume.empty())
            return execute_new_run(*args, global, checkpoints->interval);
        // A resumed run is the recorded run: nothing else may change it.
        for (const CLI::Option* opt : cmd->get_options())
            if (opt->count() > 0 && opt->get_name() != "--resume" && opt->get_name() != "--threads")
                throw ConfigError(
                    "--resume", "takes only --threads; the parameters are those recorded in " +
                                    checkpoints->resume + "/checkpoint.h5 (got " + opt->get_name() +
                                    ")");
        return execute_resume(checkpoints->resume, args->threads, global);
    };
}

}  // namespace avalanche::detail
