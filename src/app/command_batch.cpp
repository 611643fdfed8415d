// `avalanche-hazard batch`: the CLI11 registration; the work is in batch_run.cpp.
#include <memory>

#include "batch_run.hpp"

namespace avalanche::detail {

Command add_batch_command(CLI::App& app, const GlobalOptions& global) {
    auto args = std::make_shared<BatchArguments>();
    CLI::App* cmd = app.add_subcommand(
        "batch", "Run many scenarios (parameter sweeps or a table) and compare them");
    cmd->fallthrough();  // --quiet, --verbose, --debug may follow the subcommand
    cmd->add_option_function<std::string>(
        "--scenario", [args](const std::string& v) { args->scenario = v; },
        "Base scenario file (TOML); or --dem and --release (with run's other scenario flags)");
    auto* sweep = cmd->add_option(
        "--sweep", args->sweeps,
        "NAME=v1,v2,... or NAME=start:stop:step (repeatable: the Cartesian product); NAME in "
        "delta, phi, density, thickness, volume, cfl, scheme, limiter, t_end, earth_pressure, "
        "rest_faces");
    sweep->allow_extra_args(false);
    auto* table = cmd->add_option("--table", args->table,
                                  "CSV file: header of parameter names, one scenario per row");
    sweep->excludes(table);
    cmd->add_option("--out", args->out, "Output folder of the batch")->required();
    cmd->add_flag("--overwrite", args->overwrite,
                  "Recompute every scenario, even those a previous batch completed");
    cmd->add_option("--parallel", args->parallel,
                    "Scenarios run at a time per process (default: its share of the cores)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--observed", args->observed,
                    "Polygons of an observed deposit (any OGR format and CRS): rank the "
                    "scenarios by fit (comparison.csv, calibration.json)");
    // The base scenario's flags, as `run` has them; a swept parameter's values win.
    add_scenario_flags(*cmd, args->overrides);
    // clang-format off
    cmd->footer(
        "Examples:\n"
        "  avalanche-hazard batch --scenario base.toml --sweep delta=10,12.5,15,20 \\\n"
        "      --sweep phi=25:35:5 --out out/sweep\n"
        "  avalanche-hazard batch --dem area.tif --release release.gpkg --thickness 2 \\\n"
        "      --sweep delta=15:30:5 --out out/area\n"
        "  avalanche-hazard batch --scenario base.toml --table scenarios.csv --out out/table\n"
        "  avalanche-hazard batch --scenario base.toml --sweep delta=15:30:5 \\\n"
        "      --observed deposit.shp --out out/calibration\n"
        "  mpirun -n 8 avalanche-hazard batch ... (scenarios spread over the ranks)\n"
        "Rerunning the same command resumes: complete scenarios with an unchanged\n"
        "configuration are skipped (DIR/manifest.json). See docs/batch.md.");
    // clang-format on
    return [args, &global] { return run_batch(*args, global); };
}

}  // namespace avalanche::detail
