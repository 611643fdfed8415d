// `avalanche-hazard batch`: plan the scenarios, skip those a previous batch completed,
// prepare each distinct scene once, run the rest N at a time, then compare them.
#include "batch_run.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include "avalanche/app/batch_manifest.hpp"
#include "avalanche/app/batch_plan.hpp"
#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/app/scenario_overrides.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/io/effective_config.hpp"
#include "batch_outputs.hpp"
#include "interrupt.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace avalanche::detail {

namespace {

namespace fs = std::filesystem;

struct Planned {
    BatchCase batch_case;
    Scenario scenario;
    std::string hash, dir;
    bool skip = false;
    std::shared_ptr<const PreparedScene> scene;
};

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

// Marks what a previous batch completed with the same configuration; logs the rest.
Manifest decide_skips(std::vector<Planned>& planned, const Manifest& old) {
    Manifest manifest;
    for (auto& p : planned) {
        ManifestEntry e{parameters_json(p.batch_case), p.hash, false, ""};
        const auto it = old.find(p.batch_case.id);
        const char* reason = "new";
        if (it != old.end()) {
            const bool same = it->second.config_hash == p.hash;
            p.skip = same && it->second.complete && outputs_complete(p.dir, p.hash);
            reason = !same ? "configuration changed" : "outputs incomplete";
        }
        e.complete = p.skip;
        if (p.skip)
            spdlog::info("skipping {}: complete, configuration {} unchanged", p.batch_case.id,
                         p.hash);
        else
            spdlog::info("computing {} ({})", p.batch_case.id, reason);
        manifest[p.batch_case.id] = e;
    }
    return manifest;
}

// One preparation per distinct scene: material and numerics cases share the base scene.
void attach_scenes(std::vector<Planned*>& pending) {
    std::map<std::string, std::shared_ptr<const PreparedScene>> scenes;
    for (auto* p : pending) {
        auto& scene = scenes[scene_key(p->batch_case)];
        if (!scene) scene = std::make_shared<const PreparedScene>(prepare_scene(p->scenario));
        p->scene = scene;
    }
    if (!pending.empty())
        spdlog::info("prepared {} scene(s) for {} scenario(s)", scenes.size(), pending.size());
}

struct Failure {
    std::string id, message;
    ExitCode code = ExitCode::internal;
};

// Runs the pending scenarios `workers` at a time. omp_set_num_threads sets the calling
// thread's value only, so each worker sets it for the solver loops it starts.
std::vector<Failure> run_pending(const std::vector<Planned*>& pending, Manifest& manifest,
                                 const std::string& manifest_path, const nlohmann::json& batch,
                                 int parallel, const GlobalOptions& global) {
    const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
#ifdef _OPENMP
    // The thread budget: OMP_NUM_THREADS when the user set it, else every core.
    const int budget = std::max(1, omp_get_max_threads());
#else
    const int budget = cores;
#endif
    const int workers = std::clamp(parallel > 0 ? parallel : cores, 1,
                                   std::max(1, static_cast<int>(pending.size())));
    const int omp_threads = std::max(1, budget / workers);
    spdlog::info("running {} scenario(s), {} at a time, {} OpenMP thread(s) each", pending.size(),
                 workers, omp_threads);
    std::mutex mutex;
    std::atomic<std::size_t> next{0};
    std::size_t finished = 0;
    std::vector<Failure> failures;
    auto work = [&] {
#ifdef _OPENMP
        omp_set_num_threads(omp_threads);
#endif
        for (std::size_t k; (k = next++) < pending.size() && !InterruptGuard::requested();) {
            const Planned& p = *pending[k];
            const std::string& id = p.batch_case.id;
            try {
                std::error_code ec;
                fs::remove_all(p.dir, ec);  // no stale product of an older configuration
                prepare_output_folder(p.dir, false);
                RunOptions options{p.dir, global.command_line,
                                   [](double) { return !InterruptGuard::requested(); }};
                const RunOutcome outcome = execute_scene(*p.scene, p.scenario, options);
                const std::lock_guard lock(mutex);
                const bool done = outcome.stats.end_reason != EndReason::interrupted;
                manifest[id].complete = done;
                manifest[id].error.clear();
                write_manifest(manifest_path, manifest, batch);
                spdlog::info("finished {} ({} of {}){}", id, ++finished, pending.size(),
                             done ? "" : ": interrupted");
            } catch (const std::exception& e) {
                const auto* err = dynamic_cast<const Error*>(&e);
                const std::lock_guard lock(mutex);
                failures.push_back({id, e.what(), err ? err->code() : ExitCode::internal});
                manifest[id].error = e.what();
                spdlog::error("scenario {} failed: {}", id, e.what());
                try {
                    write_manifest(manifest_path, manifest, batch);
                } catch (const std::exception&) {  // reported with the scenario's failure
                }
            }
        }
    };
    std::vector<std::thread> threads;
    for (int w = 0; w < workers; ++w) threads.emplace_back(work);
    for (auto& t : threads) t.join();
    return failures;
}

std::optional<nlohmann::json> read_summary(const std::string& dir) {
    std::ifstream in(fs::path(dir) / "summary.json");
    if (!in) return std::nullopt;
    return nlohmann::json::parse(in);
}

}  // namespace

int run_batch(const BatchArguments& args, const GlobalOptions& global) {
    const std::vector<BatchCase> cases = plan_cases(args);
    const Scenario base = assemble_scenario(args.scenario, {});
    std::vector<Planned> planned;
    for (const auto& c : cases) {
        Planned p{c,     scenario_for_case(base, c),
                  "",    (fs::path(args.out) / c.id).string(),
                  false, nullptr};
        p.hash = config_hash(effective_config(p.scenario));
        planned.push_back(std::move(p));
    }
    prepare_batch_folder(args.out, args.overwrite);
    const std::string manifest_path = (fs::path(args.out) / "manifest.json").string();
    const nlohmann::json batch = {{"base_scenario", args.scenario},
                                  {"sweeps", args.sweeps},
                                  {"table", args.table},
                                  {"software_version", software_version()}};
    Manifest manifest =
        decide_skips(planned, args.overwrite ? Manifest{} : read_manifest(manifest_path));
    write_manifest(manifest_path, manifest, batch);

    std::vector<Planned*> pending;
    for (auto& p : planned)
        if (!p.skip) pending.push_back(&p);
    spdlog::info("batch of {} scenario(s): {} to compute, {} complete", planned.size(),
                 pending.size(), planned.size() - pending.size());
    attach_scenes(pending);
    InterruptGuard interrupt;
    const auto failures =
        run_pending(pending, manifest, manifest_path, batch, args.parallel, global);

    std::vector<BatchResult> results;
    for (const auto& p : planned) {
        BatchResult r{&p.batch_case, p.dir, std::nullopt, manifest[p.batch_case.id].error};
        if (manifest[p.batch_case.id].complete) r.summary = read_summary(p.dir);
        results.push_back(std::move(r));
    }
    auto files = write_comparison(args.out, results, args.scenario);
    const auto maps = write_envelopes(args.out, results);
    files.insert(files.end(), maps.begin(), maps.end());
    spdlog::info("wrote {} comparison file(s) into {}", files.size(), args.out);
    if (!global.quiet)
        std::cout << "comparison: " << (fs::path(args.out) / "comparison.csv").string()
                  << "\nreport: " << (fs::path(args.out) / "comparison.md").string() << "\n";

    if (InterruptGuard::requested())
        throw Error(ExitCode::interrupted,
                    "interrupted; rerun the same command to resume from " + manifest_path);
    if (!failures.empty())
        throw Error(failures.front().code, std::to_string(failures.size()) + " of " +
                                               std::to_string(pending.size()) +
                                               " scenario(s) failed; first " + failures.front().id +
                                               ": " + failures.front().message);
    return 0;
}

}  // namespace avalanche::detail
