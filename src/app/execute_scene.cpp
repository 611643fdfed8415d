#include <spdlog/spdlog.h>

#include <filesystem>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/io/effective_config.hpp"
#include "avalanche/io/results_writer.hpp"
#include "avalanche/io/summary_writer.hpp"

namespace avalanche {

RunOutcome execute_scene(const PreparedScene& scene, const Scenario& s, const RunOptions& options) {
    const std::filesystem::path dir(options.out_dir);
    const double h_min = effective_h_min(s.numerics, scene.initial, scene.terrain);
    const nlohmann::json config = effective_config(s);
    const std::string hash = config_hash(config);

    Simulation sim(scene.grid, scene.terrain, s.material, s.numerics, scene.initial, h_min);
    ResultsMetadata meta{
        scene.geotransform, scene.crs_wkt, scene.frame, s.numerics.gravity, h_min, config, hash};
    ResultsWriter results((dir / "results.h5").string(), scene.grid, meta);
    sim.add_observer(&results);
    if (options.progress) sim.set_progress(options.progress);

    spdlog::info("{}; released {:.6g} m3; h_min {:.3g} m; config {}", scene.description,
                 total_volume(scene.initial, scene.grid), h_min, hash);
    const RunStatistics stats = sim.run();
    spdlog::info(
        "ended ({}) at t = {:.6g} s after {} steps in {:.3g} s wall; {:.3g} cell updates/s",
        to_string(stats.end_reason), stats.simulated_time, stats.steps, stats.wall_seconds,
        stats.cell_updates_per_second());
    spdlog::info(
        "volume: released {:.6g} m3, final {:.6g} m3, outflow {:.6g} m3, relative error {:.3g}",
        stats.released_volume, stats.final_volume, stats.outflow_volume,
        stats.relative_mass_error());

    results.finish(stats);
    SummaryInputs summary{stats,       config,     hash,        options.command_line,
                          h_min,       scene.grid, scene.frame, results.snapshots(),
                          "results.h5"};
    const std::string summary_path = (dir / "summary.json").string();
    write_summary(summary_path, summary);
    return {stats, results.path(), summary_path};
}

}  // namespace avalanche
