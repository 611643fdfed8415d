// `avalanche-hazard batch`: plan the scenarios, skip those a previous batch completed,
// prepare each distinct scene once, run the rest N at a time (on every MPI rank when
// launched by mpirun), then compare them on rank 0.
#include "batch_run.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>

#include "avalanche/app/batch_manifest.hpp"
#include "avalanche/app/batch_plan.hpp"
#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/app/report_html.hpp"
#include "avalanche/app/scenario_overrides.hpp"
#include "avalanche/app/shared_scene_products.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/io/effective_config.hpp"
#include "batch_calibration.hpp"
#include "batch_mpi.hpp"
#include "batch_outputs.hpp"
#include "interrupt.hpp"
#include "logging.hpp"
#include "work_queue.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace avalanche::detail {

namespace {

namespace fs = std::filesystem;

struct Planned {
    BatchCase batch_case;
    Scenario scenario;
    std::string hash;                // config_hash of its effective configuration
    std::string hash_without_paths;  // the same without the input paths (decide_skips)
    std::string dir;
    bool skip = false;
    std::shared_ptr<const PreparedScene> scene;
};

// Prepared scenes by scene_key: material and numerics cases share the base scene.
using SceneCache = std::map<std::string, std::shared_ptr<const PreparedScene>>;

// What the scenarios are built on, as comparison.md and report.html name it: the scenario
// file, the flags, or both ("base.toml with --delta 25").
std::string base_description(const BatchArguments& a) {
    const std::string flags = overrides_text(a.overrides);
    if (!a.scenario) return flags;
    return flags.empty() ? *a.scenario : *a.scenario + " with " + flags;
}

std::string join(const std::vector<std::string>& words) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
    return out;
}

std::vector<BatchCase> plan_cases(const BatchArguments& a) {
    if (a.sweeps.empty() == a.table.empty())
        throw ConfigError("--sweep", "expected --sweep NAME=VALUES (repeatable) or --table FILE");
    if (!a.table.empty()) return read_case_table(a.table);
    std::vector<Sweep> sweeps;
    for (const auto& s : a.sweeps) sweeps.push_back(parse_sweep(s));
    return cartesian_product(sweeps);
}

// The batch owns DIR: a folder of a single run, or a folder with other files and no
// manifest, is refused unless --overwrite, so a typo in --out cannot mix results.
void prepare_batch_folder(const std::string& out, bool overwrite) {
    std::error_code ec;
    const fs::path d(out);
    if (fs::is_directory(d, ec) && !overwrite) {
        for (const char* product : {"summary.json", "results.h5"})
            if (fs::exists(d / product, ec))
                throw OutputError(out, std::string("holds the results of a single run (") +
                                           product + "); a batch needs its own folder");
        if (!fs::exists(d / "manifest.json", ec) && !fs::is_empty(d, ec))
            throw OutputError(out,
                              "holds files but no batch manifest.json; use --overwrite "
                              "or an empty folder");
    }
    prepare_output_folder(out, /*overwrite=*/true);  // creates it, checks it is writable
}

nlohmann::json parameters_json(const BatchCase& c) {
    nlohmann::json p = nlohmann::json::object();
    for (const auto& [param, v] : c.values)
        p[param->column] = param->numeric ? nlohmann::json(std::stod(v)) : nlohmann::json(v);
    return p;
}

const std::shared_ptr<const PreparedScene>& scene_of(const Planned& p, SceneCache& scenes) {
    auto& scene = scenes[scene_key(p.batch_case)];
    if (!scene) scene = std::make_shared<const PreparedScene>(prepare_scene(p.scenario));
    return scene;
}

// Marks what a previous batch completed with the same configuration, from the same
// sources and on the same inputs; logs the rest. The configurations are compared without
// their input paths (which depend on the working folder the batch started in), and the
// inputs as prepared (the scene fingerprint its summary.json records; a DEM edited in
// place keeps its path): the scenes of the scenarios that pass every other test are
// prepared here, and kept in `scenes` for the runs.
Manifest decide_skips(std::vector<Planned>& planned, const Manifest& old, SceneCache& scenes) {
    Manifest manifest;
    const std::string sources = source_hash();
    std::map<std::string, std::string> fingerprints;  // the scenes' now, by scene_key
    for (auto& p : planned) {
        ManifestEntry e{parameters_json(p.batch_case), p.hash, p.hash_without_paths, sources,
                        false, ""};
        const auto it = old.find(p.batch_case.id);
        std::string reason = "new", fingerprint;
        if (it != old.end()) {
            const bool recorded_hash = !it->second.config_hash_without_paths.empty();
            const bool same = it->second.config_hash_without_paths == p.hash_without_paths;
            const bool same_sources = it->second.source_hash == sources;
            const std::optional<std::string> recorded =
                same && same_sources && it->second.complete
                    ? completed_run_fingerprint(p.dir, p.hash_without_paths, sources)
                    : std::nullopt;
            reason = !recorded_hash      ? "computed before the batch recorded its inputs"
                     : !same             ? "configuration changed"
                     : !same_sources     ? "computed by a program built from other sources"
                     : !recorded         ? "outputs incomplete"
                     : recorded->empty() ? "its summary records no fingerprint of its inputs"
                                         : "inputs changed: the terrain, release or monitoring "
                                           "points prepare to another scene than the one it was "
                                           "computed on";
            if (recorded && !recorded->empty()) {
                std::string& now = fingerprints[scene_key(p.batch_case)];
                if (now.empty()) {
                    const auto& scene = scene_of(p, scenes);
                    now = scene_fingerprint_of(*scene, scene->initial);
                }
                fingerprint = now;
                p.skip = *recorded == now;
            }
        }
        e.complete = p.skip;
        if (p.skip)
            spdlog::info("skipping {}: complete, configuration {}, sources {} and inputs {} unchanged",
                         p.batch_case.id, p.hash_without_paths, sources, fingerprint);
        else
            spdlog::info("computing {} ({})", p.batch_case.id, reason);
        manifest[p.batch_case.id] = e;
    }
    return manifest;
}

// One preparation per distinct scene (reusing those prepared already, e.g. for --observed).
void attach_scenes(std::vector<Planned*>& pending, SceneCache& scenes) {
    for (auto* p : pending) p->scene = scene_of(*p, scenes);
    if (!pending.empty())
        spdlog::info("prepared {} scene(s) for {} scenario(s)", scenes.size(), pending.size());
}

struct Failure {
    std::string id, message;
    ExitCode code = ExitCode::internal;
};

// Runs the pending scenarios `workers` at a time. omp_set_num_threads sets the calling
// thread's value only, so each worker sets it for the solver loops it starts. The cores
// are shared with the other MPI ranks on the machine (`ranks_on_node`). Only the process
// that owns the manifest (rank 0) rewrites it as scenarios finish.
std::vector<Failure> run_pending(const std::vector<Planned*>& pending, Manifest& manifest,
                                 const std::string& manifest_path, const nlohmann::json& batch,
                                 int parallel, int ranks_on_node, bool owns_manifest,
                                 const GlobalOptions& global) {
    if (pending.empty()) return {};  // e.g. an MPI rank with no share of the scenarios
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
#ifdef _OPENMP
    // The thread budget: OMP_NUM_THREADS when the user set it, else every core.
    const int budget = std::max(1, omp_get_max_threads() / ranks_on_node);
#else
    const int budget = std::max(1, cores / ranks_on_node);
#endif
    const int workers = std::clamp(parallel > 0 ? parallel : std::max(1, cores / ranks_on_node), 1,
                                   std::max(1, static_cast<int>(pending.size())));
    const int omp_threads = std::max(1, budget / workers);
    spdlog::info("running {} scenario(s), {} at a time, {} OpenMP thread(s) each", pending.size(),
                 workers, omp_threads);
    // What the scenarios of one scene share in their products, made before the workers
    // start so that none of them inserts into the map.
    std::map<const PreparedScene*, std::unique_ptr<SharedSceneProducts>> shared;
    for (const Planned* p : pending)
        if (!shared[p->scene.get()]) shared[p->scene.get()] = std::make_unique<SharedSceneProducts>();
    std::mutex mutex;
    std::size_t finished = 0;
    std::vector<Failure> failures;
    auto save_manifest = [&] {
        if (owns_manifest) write_manifest(manifest_path, manifest, batch);
    };
    const auto run_one = [&](std::size_t k) {
        const Planned& p = *pending[k];
        const std::string& id = p.batch_case.id;
        // Every log line of this scenario, from this thread, names it.
        const ScopedLogContext context(id);
        try {
            std::error_code ec;
            fs::remove_all(p.dir, ec);  // no stale product of an older configuration
            prepare_output_folder(p.dir, false);
            RunOptions options{p.dir, global.command_line,
                               [](double) { return !InterruptGuard::requested(); }};
            options.shared_products = shared.at(p.scene.get()).get();
            const RunOutcome outcome = execute_scene(*p.scene, p.scenario, options);
            const std::lock_guard lock(mutex);
            const bool done = outcome.stats.end_reason != EndReason::interrupted;
            manifest[id].complete = done;
            manifest[id].error.clear();
            manifest[id].interrupted = !done;
            save_manifest();
            spdlog::info("finished ({} of {}){}", ++finished, pending.size(),
                         done ? "" : ": interrupted");
        } catch (const std::exception& e) {
            const auto* err = dynamic_cast<const Error*>(&e);
            const std::lock_guard lock(mutex);
            failures.push_back({id, e.what(), err ? err->code() : ExitCode::internal});
            manifest[id].complete = false;
            manifest[id].error = e.what();
            spdlog::error("failed: {}", e.what());
            try {
                save_manifest();
            } catch (const std::exception&) {  // reported with the scenario's failure
            }
        }
    };
    run_on_threads(pending.size(), workers, run_one, [] { return InterruptGuard::requested(); },
                   [omp_threads] {
#ifdef _OPENMP
                       omp_set_num_threads(omp_threads);
#else
                       (void)omp_threads;
#endif
                   });
    return failures;
}

// What a rank sends rank 0 after its runs: each of its scenarios' outcome.
std::string rank_report(const std::vector<Planned*>& mine, Manifest& manifest,
                        const std::vector<Failure>& failures) {
    nlohmann::json r = {{"scenarios", nlohmann::json::array()},
                        {"failures", nlohmann::json::array()},
                        {"interrupted", InterruptGuard::requested()}};
    for (const auto* p : mine) {
        const auto& e = manifest[p->batch_case.id];
        r["scenarios"].push_back({{"id", p->batch_case.id},
                                  {"complete", e.complete},
                                  {"error", e.error},
                                  {"interrupted", e.interrupted}});
    }
    for (const auto& f : failures)
        r["failures"].push_back(
            {{"id", f.id}, {"message", f.message}, {"code", static_cast<int>(f.code)}});
    return r.dump();
}

std::optional<nlohmann::json> read_summary(const std::string& dir) {
    std::ifstream in(fs::path(dir) / "summary.json");
    if (!in) return std::nullopt;
    return nlohmann::json::parse(in);
}

// Every across-scenario output of DIR, from what the scenarios wrote into DIR/<id>/: the
// one place where the comparison files are written (by one process: rank 0).
void write_batch_outputs(const BatchArguments& args, std::vector<BatchResult>& results,
                         const std::optional<Observation>& observation,
                         const GlobalOptions& global) {
    if (observation) fit_to_observation(*observation, results);
    const std::string base = base_description(args);
    auto files = write_comparison(args.out, results, base, args.observed);
    const auto maps = write_envelopes(args.out, results);
    files.insert(files.end(), maps.begin(), maps.end());
    if (observation) files.push_back(write_calibration(args.out, *observation, results));
    for (const auto& f : write_batch_report_html(args.out, base, files)) files.push_back(f);
    spdlog::info("wrote {} comparison file(s) into {}", files.size(), args.out);
    if (!global.quiet)
        std::cout << "comparison: " << (fs::path(args.out) / "comparison.csv").string()
                  << "\nreport: " << (fs::path(args.out) / "comparison.md").string() << "\n";
}

int run_batch_on(const BatchRanks& ranks, const BatchArguments& args, const GlobalOptions& global) {
    // Planning is deterministic, so every rank plans the same batch (and refuses the same
    // bad values; all_or_none lets only rank 0 say so).
    std::vector<BatchCase> cases;
    std::vector<Planned> planned;
    Scenario base;
    ranks.all_or_none([&] {
        cases = plan_cases(args);
        base = assemble_scenario(args.scenario, args.overrides);
        // Every case sets the same parameters, so the first says which flags they replace.
        const auto replaced =
            cases.empty() ? std::vector<std::string>{} : flags_replaced_by(cases.front(), args.overrides);
        if (!replaced.empty() && ranks.root())
            spdlog::warn("{} replaced in every scenario by the {}'s values", join(replaced),
                         args.table.empty() ? "sweep" : "table");
        for (const auto& c : cases) {
            Scenario scenario = scenario_for_case(base, c);
            const nlohmann::json config = effective_config(scenario);
            planned.push_back(Planned{c, std::move(scenario), config_hash(config),
                                      config_hash_without_paths(config),
                                      (fs::path(args.out) / c.id).string(), false, nullptr});
        }
    });

    // Rank 0 owns DIR: the observed deposit is checked before DIR is touched, so a bad
    // --observed leaves no product behind.
    const std::string manifest_path = (fs::path(args.out) / "manifest.json").string();
    const nlohmann::json batch = {{"base_scenario", args.scenario ? nlohmann::json(*args.scenario)
                                                                  : nlohmann::json(nullptr)},
                                  {"base_flags", overrides_text(args.overrides)},
                                  {"sweeps", args.sweeps},
                                  {"table", args.table},
                                  {"observed", args.observed},
                                  {"software_version", software_version()},
                                  {"source_hash", source_hash()}};
    SceneCache scenes;
    std::optional<Observation> observation;
    Manifest manifest;
    ranks.all_or_none([&] {
        if (!ranks.root()) return;
        if (!args.observed.empty())
            observation = load_observation(args.observed, *scene_of(planned.front(), scenes),
                                           base.output.h_threshold);
        prepare_batch_folder(args.out, args.overwrite);
        manifest = decide_skips(planned, args.overwrite ? Manifest{} : read_manifest(manifest_path),
                                scenes);
        write_manifest(manifest_path, manifest, batch);
    });
    std::string skips;
    for (const auto& p : planned) skips += p.skip ? '1' : '0';
    skips = ranks.broadcast(skips);
    for (std::size_t k = 0; k < planned.size(); ++k) planned[k].skip = skips[k] == '1';

    // Static round-robin over the ranks: pending scenario k runs on rank k mod N.
    std::vector<Planned*> pending, mine;
    for (auto& p : planned)
        if (!p.skip) pending.push_back(&p);
    for (std::size_t k = 0; k < pending.size(); ++k)
        if (static_cast<int>(k % static_cast<std::size_t>(ranks.size())) == ranks.rank())
            mine.push_back(pending[k]);
    if (ranks.root())
        spdlog::info("batch of {} scenario(s): {} to compute, {} complete", planned.size(),
                     pending.size(), planned.size() - pending.size());
    if (ranks.size() > 1)
        spdlog::info("MPI rank {} of {}: {} scenario(s)", ranks.rank(), ranks.size(), mine.size());
    // Scenes prepared to compare the inputs of scenarios that are skipped, or that another
    // rank runs, are not kept through the runs.
    std::set<std::string> needed;
    for (const auto* p : mine) needed.insert(scene_key(p->batch_case));
    std::erase_if(scenes, [&](const auto& kv) { return !needed.count(kv.first); });
    ranks.all_or_none([&] { attach_scenes(mine, scenes); });
    InterruptGuard interrupt;
    std::vector<Failure> failures = run_pending(mine, manifest, manifest_path, batch, args.parallel,
                                                ranks.ranks_on_node(), ranks.root(), global);

    // Rank 0 learns every rank's outcomes, records them, and decides the exit code.
    const auto reports = ranks.gather(rank_report(mine, manifest, failures));
    bool interrupted = false;
    if (ranks.root() && ranks.size() > 1) {
        failures.clear();
        for (const auto& text : reports) {
            const auto r = nlohmann::json::parse(text);
            interrupted = interrupted || r.at("interrupted").get<bool>();
            for (const auto& s : r.at("scenarios")) {
                auto& e = manifest[s.at("id").get<std::string>()];
                e.complete = s.at("complete").get<bool>();
                e.error = s.at("error").get<std::string>();
                e.interrupted = s.at("interrupted").get<bool>();
            }
            for (const auto& f : r.at("failures"))
                failures.push_back({f.at("id").get<std::string>(),
                                    f.at("message").get<std::string>(),
                                    static_cast<ExitCode>(f.at("code").get<int>())});
        }
        // The first failure in the batch's own order, whichever rank ran it.
        std::stable_sort(failures.begin(), failures.end(), [&](const Failure& a, const Failure& b) {
            auto at = [&](const std::string& id) {
                return std::find_if(planned.begin(), planned.end(),
                                    [&](const Planned& p) { return p.batch_case.id == id; }) -
                       planned.begin();
            };
            return at(a.id) < at(b.id);
        });
        write_manifest(manifest_path, manifest, batch);
    }
    interrupted = interrupted || InterruptGuard::requested();
    const int code = ranks.broadcast_code(
        interrupted ? static_cast<int>(ExitCode::interrupted)
                    : (failures.empty() ? 0 : static_cast<int>(failures.front().code)));
    if (!ranks.root()) return code;  // rank 0 writes DIR and reports

    // Only complete scenarios are compared; the others say why from the manifest, since an
    // interrupted one's summary.json (end_reason "interrupted") and a folder left by an
    // earlier batch for a scenario this one never started are not results of this batch.
    std::vector<BatchResult> results;
    for (const auto& p : planned) {
        const ManifestEntry& e = manifest[p.batch_case.id];
        const ScenarioOutcome outcome = e.complete         ? ScenarioOutcome::complete
                                        : !e.error.empty() ? ScenarioOutcome::failed
                                        : e.interrupted    ? ScenarioOutcome::interrupted
                                                           : ScenarioOutcome::not_run;
        BatchResult r{&p.batch_case, p.dir, std::nullopt, e.error, {}, outcome};
        if (e.complete) r.summary = read_summary(p.dir);
        results.push_back(std::move(r));
    }
    write_batch_outputs(args, results, observation, global);

    if (interrupted)
        throw Error(ExitCode::interrupted,
                    "interrupted; rerun the same command to resume from " + manifest_path);
    if (!failures.empty())
        throw Error(failures.front().code, std::to_string(failures.size()) + " of " +
                                               std::to_string(pending.size()) +
                                               " scenario(s) failed; first " + failures.front().id +
                                               ": " + failures.front().message);
    return 0;
}

}  // namespace

int run_batch(const BatchArguments& args, const GlobalOptions& global) {
    const BatchRanks ranks;  // MPI_Init only when launched by mpirun/srun
    try {
        return run_batch_on(ranks, args, global);
    } catch (const QuietRankExit& e) {
        return e.code;
    }
}

}  // namespace avalanche::detail
