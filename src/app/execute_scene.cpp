#include <spdlog/spdlog.h>

#include <filesystem>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/app/products.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/effective_config.hpp"
#include "avalanche/io/results_writer.hpp"
#include "avalanche/io/summary_writer.hpp"
#include "avalanche/output/hazard_maps.hpp"
#include "avalanche/output/monitoring.hpp"
#include "avalanche/output/runout.hpp"

namespace avalanche {

namespace {

nlohmann::json runout_json(const RunoutMetrics& r) {
    return {{"runout_length_m", r.runout_length_m},
            {"fall_height_m", r.fall_height_m},
            {"travel_angle_deg", r.travel_angle_deg},
            {"runout_efficiency", r.runout_efficiency},
            {"affected_area_m2", r.affected_area_m2},
            {"deposit_volume_m3", r.deposit_volume_m3},
            {"max_depth_m", r.max_depth_m},
            {"max_velocity_ms", r.max_velocity_ms},
            {"max_pressure_kpa", r.max_pressure_kpa},
            {"release_top_xy", r.top_xy},
            {"runout_tip_xy", r.tip_xy}};
}

nlohmann::json monitoring_json(const MonitoringPoints& probes, const HazardMaps& maps, const Grid& g) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& p : probes.points()) {
        const std::size_t k = static_cast<std::size_t>(p.j) * g.nx + p.i;
        const double a = maps.arrival_time()[k];
        out.push_back({{"name", p.name},
                       {"x", p.x},
                       {"y", p.y},
                       {"arrival_time_s", a == HazardMaps::kNotReached ? nlohmann::json(nullptr) : nlohmann::json(a)},
                       {"max_depth_m", maps.max_depth()[k]},
                       {"max_velocity_ms", maps.max_speed()[k]},
                       {"max_pressure_kpa", maps.max_pressure()[k]}});
    }
    return out;
}

}  // namespace

RunOutcome execute_scene(const PreparedScene& scene, const Scenario& s, const RunOptions& options) {
    const std::filesystem::path dir(options.out_dir);
    const double h_min = effective_h_min(s.numerics, scene.initial, scene.terrain);
    const nlohmann::json config = effective_config(s);
    const std::string hash = config_hash(config);

    Simulation sim(scene.grid, scene.terrain, s.material, s.numerics, scene.initial, h_min);
    if (!scene.outside_data.empty()) sim.set_sink_cells(scene.outside_data);
    ResultsMetadata meta{
        scene.geotransform, scene.crs_wkt, scene.frame, s.numerics.gravity, h_min, config, hash};
    ResultsWriter results((dir / "results.h5").string(), scene.grid, meta);
    HazardMaps maps(scene.grid, s.output, s.material.density);
    // Monitoring series every tenth of the snapshot interval: fine enough to see a
    // front pass a point, small enough to keep the CSV readable.
    MonitoringPoints probes(scene.probes, s.numerics.output_interval / 10.0, s.material.density);
    sim.add_observer(&results);
    sim.add_observer(&maps);
    if (!scene.probes.empty()) sim.add_observer(&probes);
    if (options.progress) sim.set_progress(options.progress);

    for (const auto& note : scene.input_notes) spdlog::info("{}", note);
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
    const RunoutMetrics runout = compute_runout(scene.grid, scene.terrain, scene.initial, maps, s.output,
                                                scene.horizontal_position, scene.cell_area_m2);
    const ProductInputs products{scene, s, maps, scene.probes.empty() ? nullptr : &probes, stats, runout, hash,
                                 options.command_line};
    const std::vector<std::string> files = write_products(options.out_dir, products);
    write_report(options.out_dir, products, files);
    spdlog::info("runout {:.1f} m, travel angle {:.1f} deg, affected area {:.0f} m2; wrote {} product files",
                 runout.runout_length_m, runout.travel_angle_deg, runout.affected_area_m2, files.size() + 1);

    // summary.json last: its presence says the run and every product are complete.
    SummaryInputs summary{stats,       config,     hash,        options.command_line,
                          h_min,       scene.grid, scene.frame, results.snapshots(),
                          "results.h5"};
    nlohmann::json js = make_summary(summary);
    js["runout"] = runout_json(runout);
    if (!scene.probes.empty()) js["monitoring_points"] = monitoring_json(probes, maps, scene.grid);
    js["products"] = files;
    js["products"].push_back("report.md");
    js["crs_wkt"] = scene.crs_wkt;
    js["inputs"] = scene.input_files;
    const std::string summary_path = (dir / "summary.json").string();
    write_file_atomically(summary_path, js.dump(2) + "\n");
    return {stats, results.path(), summary_path};
}

}  // namespace avalanche
