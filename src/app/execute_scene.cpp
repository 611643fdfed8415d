#include <spdlog/spdlog.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "avalanche/app/malloc_huge_pages.hpp"
#include "avalanche/app/openmp_wait.hpp"
#include "avalanche/app/phase_times.hpp"
#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/app/products.hpp"
#include "avalanche/app/report_html.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/checkpoint_file.hpp"
#include "avalanche/io/effective_config.hpp"
#include "avalanche/io/results_writer.hpp"
#include "avalanche/io/summary_writer.hpp"
#include "avalanche/output/hazard_maps.hpp"
#include "avalanche/output/monitoring.hpp"
#include "avalanche/output/run_caveats.hpp"
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
        const double a = maps.arrival_time(k);
        out.push_back({{"name", p.name},
                       {"x", p.x},
                       {"y", p.y},
                       {"arrival_time_s", a == HazardMaps::kNotReached ? nlohmann::json(nullptr) : nlohmann::json(a)},
                       {"max_depth_m", maps.max_depth()[k]},
                       {"max_velocity_ms", maps.max_speed()[k]},
                       {"max_pressure_kpa", maps.max_pressure(k)}});
    }
    return out;
}

// Removes what a failed run must not leave looking complete (a previous run's summary
// and results, with --overwrite).
void remove_complete_markers(const std::filesystem::path& dir) {
    std::error_code ec;
    std::filesystem::remove(dir / "summary.json", ec);
    std::filesystem::remove(dir / "results.h5", ec);
}

// Godunov whose advections run at Courant 0.2 or more stops converging under
// refinement on the Savage-Hutter cap released from rest (docs/verification.md, finding
// 2: E1 at dx 0.05, 0.025, 0.0125 m 1.7e-2, 9.1e-3, 9.6e-3 with L S L at Courant 0.4,
// and 1.5e-2, 1.2e-2, 2.7e-2 with S L S at 0.4, against 1.9e-2, 9.6e-3, 5.0e-3 for the
// default L S L at 0.2; WAF converges at all of them). Not refused: on the other
// verification cases those runs are sound; said, so that a map made that way is checked
// against the default.
std::optional<std::string> numerics_caution(const NumericsParams& n, const MaterialParams& m) {
    const double c = advection_courant(n);
    if (n.scheme != Scheme::godunov || m.earth_pressure != EarthPressureModel::savage_hutter ||
        c < 0.2)
        return std::nullopt;
    return fmt::format(
        "numerics: Godunov advecting at Courant {:.3g} (cfl {:.3g}, {}); with Savage-Hutter "
        "pressure the first-order scheme stopped converging under refinement at Courant 0.2 and "
        "more per advection on a mass released from rest, on cells where its default (cfl 0.2, "
        "L S L) converged; WAF converged at both (docs/verification.md, finding 2)",
        c, n.cfl, n.splitting == Splitting::lsl ? "L S L" : "S L S");
}

int openmp_threads() {
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

// The cells that hold material (interior, row-major): the release outline of the report.
// Only those of `holding` can (PreparedScene::material_box).
std::vector<std::uint8_t> cells_with_material(const State& state, const Grid& g, const ActiveBox& holding) {
    std::vector<std::uint8_t> cells(g.cells());
    for (int j = holding.j0; j < holding.j1; ++j)
        for (int i = holding.i0; i < holding.i1; ++i)
            cells[static_cast<std::size_t>(j) * g.nx + i] = state.h(i, j) > 0.0;
    return cells;
}

// Both overloads of execute_scene: `initial` is the scene's initial state (copied or
// moved out of it); scene.initial is not read. Of `initial` only the scene's
// material_box is read (its cells outside are zero).
RunOutcome execute(const PreparedScene& scene, State initial, const Scenario& s,
                   const RunOptions& options) {
    PhaseTimes phases;
    if (options.prepare_seconds >= 0.0) phases.add("prepare", options.prepare_seconds);
    const std::filesystem::path dir(options.out_dir);
    const ActiveBox holding = scene.material_box();
    const double h_min = effective_h_min(s.numerics, initial, scene.terrain, holding);
    const nlohmann::json config = effective_config(s);
    const std::string hash = config_hash(config);
    const std::string checkpoint_path = (dir / "checkpoint.h5").string();
    const std::string diagnostic_path = (dir / "diagnostic_checkpoint.h5").string();
    const CheckpointContents* resume = options.resume;
    const CheckpointInfo checkpoint_info{
        config,
        hash,
        std::filesystem::current_path().string(),
        scene_fingerprint_of(scene, initial),
        options.checkpoint_interval,
        openmp_threads(),
        software_version(),
        source_hash()};
    if (resume && (resume->info.scene_fingerprint != checkpoint_info.scene_fingerprint ||
                   resume->nx != scene.grid.nx || resume->ny != scene.grid.ny))
        throw InputError(resume->path,
                         "the inputs changed since the checkpoint was written (the prepared terrain, "
                         "release or monitoring points differ); start a new run instead of --resume");

    {
        // A checkpoint left by an earlier run in this folder belongs to that run: a later
        // --resume must not continue it over this run's products.
        std::error_code ec;
        if (!resume) std::filesystem::remove(checkpoint_path, ec);
        std::filesystem::remove(diagnostic_path, ec);
    }

    // What the products need of the initial state, before it moves into the simulation:
    // the solver then holds the only copy (24 bytes per cell less at the peak).
    const double released_volume = total_volume(initial, scene.grid, holding);
    const ReleaseTop top = release_top(scene.grid, scene.terrain, initial, s.output.h_threshold, holding);
    const std::vector<std::uint8_t> release_cells = cells_with_material(initial, scene.grid, holding);
    // Alive for the run only: the products need the maps and the statistics, not the
    // solver's state and its advection buffer (6 doubles per cell), whose memory they
    // can reuse. (The terrain belongs to the scene and stays.)
    std::optional<Simulation> sim(std::in_place, scene.grid, scene.terrain, s.material, s.numerics,
                                  std::move(initial), h_min, holding);
    if (!scene.outside_data.empty()) sim->set_sink_cells(scene.outside_data);
    ResultsMetadata meta{
        scene.geotransform, scene.crs_wkt, scene.frame, s.numerics.gravity, h_min, config, hash};
    ResultsWriter results((dir / "results.h5").string(), scene.grid, meta);
    HazardMaps maps(scene.grid, s.output, s.material.density);
    // Monitoring series every tenth of the snapshot interval: fine enough to see a
    // front pass a point, small enough to keep the CSV readable.
    MonitoringPoints probes(scene.probes, s.numerics.output_interval / 10.0, s.material.density,
                            s.output.h_threshold);
    sim->add_observer(&results);
    sim->add_observer(&maps);
    if (!scene.probes.empty()) sim->add_observer(&probes);
    if (options.progress) sim->set_progress(options.progress);
    sim->set_checkpointing(options.checkpoint_interval, [&](const SimulationCheckpoint& c) {
        write_checkpoint(checkpoint_path, checkpoint_info, c, scene.grid, &results);
        spdlog::debug("checkpoint at t = {:.6g} s (step {}) in {}", c.loop.t, c.loop.steps, checkpoint_path);
    });
    bool diagnostic_written = false;
    sim->set_fault_handler([&](const FaultReport& f) {
        try {
            write_diagnostic_checkpoint(diagnostic_path, checkpoint_info, f, scene.grid);
            diagnostic_written = true;
        } catch (const Error& e) {
            spdlog::warn("could not write the diagnostic checkpoint: {}", e.what());
        }
    });
    // Test hook (tests/cli/test_checkpoint_signals.cpp): a NaN after step N exercises
    // the numerical-fault path end to end, which no physical scene reaches on purpose.
    if (const char* step = std::getenv("AVALANCHE_TEST_FAULT_AFTER_STEP"))
        sim->inject_fault_after_step(std::strtoull(step, nullptr, 10));
    if (resume) {
        try {
            results.resume_from(resume->path);
            sim->resume(resume->loop, resume->h, resume->hu, resume->hv, resume->observers);
        } catch (const InputError& e) {
            // The core names the checkpoint generically; say which file.
            throw InputError(resume->path, std::string("cannot resume: ") + e.what());
        }
        spdlog::info("resuming from {} at t = {:.6g} s (step {}, {} snapshots)", resume->path, resume->loop.t,
                     resume->loop.steps, results.snapshots());
    }

    for (const auto& note : scene.input_notes) spdlog::info("{}", note);
    spdlog::info("{}; released {:.6g} m3; h_min {:.3g} m; config {}", scene.description,
                 released_volume, h_min, hash);
    if (const auto caution = numerics_caution(s.numerics, s.material)) spdlog::warn("{}", *caution);
    phases.lap("setup");
    RunStatistics stats;
    try {
        stats = sim->run();
    } catch (const NumericalError& e) {
        remove_complete_markers(dir);
        throw Error(ExitCode::numerical,
                    std::string(e.what()) + (diagnostic_written
                                                 ? "; the last good and the failing state are in " + diagnostic_path
                                                 : "; no diagnostic checkpoint could be written"));
    }
    sim.reset();
    phases.lap("simulate");
    const bool complete = stats.end_reason != EndReason::interrupted;
    if (!complete)
        spdlog::info("interrupted: the products below are marked incomplete; continue with "
                     "avalanche-hazard run --resume {}",
                     dir.string());
    spdlog::info(
        "ended ({}) at t = {:.6g} s after {} steps in {:.3g} s wall; {:.3g} cell updates/s",
        to_string(stats.end_reason), stats.simulated_time, stats.steps, stats.wall_seconds,
        stats.cell_updates_per_second());
    // A run that ended by time may have been about to stop, or far from it: the ratio
    // the stop rule compares (docs/numerics.md, "End of a run").
    spdlog::info(
        "kinetic energy at the end: {:.2g} of its maximum "
        "(the stop rule: below {:.2g} for {:.3g} s)",
        stats.final_kinetic_energy_fraction(), s.numerics.stop_ke_fraction,
        s.numerics.stop_duration);
    spdlog::info(
        "volume: released {:.6g} m3, final {:.6g} m3, outflow {:.6g} m3, relative error {:.3g}",
        stats.released_volume, stats.final_volume, stats.outflow_volume,
        stats.relative_mass_error());

    results.finish(stats);
    phases.lap("results");
    const RunoutMetrics runout = compute_runout(scene.grid, scene.terrain, top, maps, s.output,
                                                scene.horizontal_position, scene.cell_area_m2);
    const std::vector<RunCaveat> caveats = run_caveats(
        {stats,
         edge_contact(scene.grid, maps.max_depth(), s.output.h_threshold, scene.outside_data,
                      maps.reach_box()),
         scene.frame, s.numerics, s.output.h_threshold});
    const ProductInputs products{scene,
                                 release_cells,
                                 s,
                                 maps,
                                 scene.probes.empty() ? nullptr : &probes,
                                 stats,
                                 runout,
                                 caveats,
                                 hash,
                                 options.command_line,
                                 options.shared_products};
    const std::vector<std::string> files = write_products(options.out_dir, products);
    phases.lap("products");
    write_report(options.out_dir, products, files);
    spdlog::info("runout {:.1f} m, travel angle {:.1f} deg, affected area {:.0f} m2; wrote {} product files",
                 runout.runout_length_m, runout.travel_angle_deg, runout.affected_area_m2, files.size() + 1);
    // Last, so that they are not scrolled away by the lines above.
    for (const auto& c : caveats) spdlog::warn("{}", c.message);

    // summary.json last: its presence says every product is written; "complete" says
    // whether the run reached its end (false after a signal: --resume continues it).
    SummaryInputs summary{stats,       config,     hash,        options.command_line,
                          h_min,       scene.grid, scene.frame, results.snapshots(),
                          "results.h5"};
    nlohmann::json js = make_summary(summary);
    js["runout"] = runout_json(runout);
    js["caveats"] = nlohmann::json::array();
    for (const auto& c : caveats) js["caveats"].push_back({{"code", c.code}, {"message", c.message}});
    if (!scene.probes.empty()) js["monitoring_points"] = monitoring_json(probes, maps, scene.grid);
    js["products"] = files;
    js["products"].push_back("report.md");
    js["products"].push_back("report.html");
    js["crs_wkt"] = scene.crs_wkt;
    js["inputs"] = scene.input_files;
    js["scene_fingerprint"] = checkpoint_info.scene_fingerprint;
    js["config_hash_without_paths"] = config_hash_without_paths(config);
    write_report_html(options.out_dir, products, js);  // from the same numbers as summary.json
    phases.lap("report");
    js["performance"]["phases_s"] = phases.to_json();
    js["performance"]["openmp_wait"] = openmp_wait_in_effect();
    js["performance"]["malloc_huge_pages"] = malloc_huge_pages_in_effect();
    spdlog::info("wall time: {}", phases.describe());
    const std::string summary_path = (dir / "summary.json").string();
    write_file_atomically(summary_path, js.dump(2) + "\n");
    return {stats, results.path(), summary_path};
}

}  // namespace

std::string scene_fingerprint_of(const PreparedScene& scene, const State& initial) {
    return scene_fingerprint(scene.grid, scene.terrain, initial, scene.material_box(), scene.outside_data,
                             scene.probes);
}

RunOutcome execute_scene(const PreparedScene& scene, const Scenario& s, const RunOptions& options) {
    return execute(scene, scene.initial_copy(), s, options);
}

RunOutcome execute_scene(PreparedScene&& scene, const Scenario& s, const RunOptions& options) {
    State initial = std::move(scene.initial);
    return execute(scene, std::move(initial), s, options);
}

}  // namespace avalanche
