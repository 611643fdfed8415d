// Whole-scene benchmarks (docs/performance.md): wall time, simulated time, steps,
// cell updates per second, threads, peak memory and bytes per cell.
//
//   bench_runs [--case a|b|c|d|all] [--scheme waf|godunov|both] [--threads N]
//              [--steps N] [--repeat N] [--splitting lsl|sls] [--data-peak on|off]
//              [--json out.jsonl]
//
// --splitting replaces the scenes' splitting (default: the paper's L S L, two
// advections per step; sls advects once per step, as the draft and fine presets do).
// --data-peak off skips the untimed run after the timed ones that measures the run's
// own data (data_peak_bytes below), which doubles the time of a case run once.
//
// (a) fully wet 1000 x 1000 tilted-plane DEM, fixed step count (default 50);
// (b) the paper's chute at 0.2 m cells, until the flow stops;
// (c) a 400 x 1000 synthetic valley DEM (10 m cells), 200 m release 20 m thick;
// (d) a small release on a 2000 x 2000 DEM and on a 200 x 200 crop of it, the same
//     simulated time: the ratio of wall times shows what the grid size costs when the
//     solver works on the active box only.
// Each (case, scheme) runs in its own child process, so that ru_maxrss is the peak
// of that case alone and not of the largest case run before it.
#include <sys/wait.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "avalanche/core/error.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/io/enum_names.hpp"
#include "bench_scenes.hpp"
#include "run_record.hpp"
#include "support/resident_memory.hpp"

using namespace avalanche;
using namespace avalanche::bench;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct Options {
    std::string which = "all";
    std::string scheme = "both";
    int threads = 0;  // 0: leave OMP_NUM_THREADS / the runtime default
    long steps = -1;  // -1: each case's default
    int repeat = 1;
    std::optional<Splitting> splitting;  // unset: the scene's (the default L S L)
    bool data_peak = true;
    std::string json;
};

[[noreturn]] void usage(const std::string& why) {
    std::cerr
        << "bench_runs: " << why
        << "\nusage: bench_runs [--case a|b|c|d|all] [--scheme waf|godunov|both] [--threads N]"
           " [--steps N] [--repeat N] [--splitting lsl|sls] [--data-peak on|off]"
           " [--json out.jsonl]\n";
    std::exit(2);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        if (k + 1 >= argc) usage("missing value after " + a);
        const std::string v = argv[++k];
        if (a == "--case")
            o.which = v;
        else if (a == "--scheme")
            o.scheme = v;
        else if (a == "--threads")
            o.threads = std::stoi(v);
        else if (a == "--steps")
            o.steps = std::stol(v);
        else if (a == "--repeat")
            o.repeat = std::stoi(v);
        else if (a == "--json")
            o.json = v;
        else if (a == "--data-peak") {
            if (v != "on" && v != "off") usage("--data-peak expects on or off");
            o.data_peak = v == "on";
        }
        else if (a == "--splitting") {
            o.splitting = enum_from_name(kSplittingNames, v);
            if (!o.splitting) usage("--splitting expects lsl or sls");
        }
        else
            usage("unknown option " + a);
    }
    if (o.which != "a" && o.which != "b" && o.which != "c" && o.which != "d" && o.which != "all")
        usage("--case expects a, b, c, d or all");
    if (o.scheme != "waf" && o.scheme != "godunov" && o.scheme != "both")
        usage("--scheme expects waf, godunov or both");
    if (o.repeat < 1 || o.threads < 0) usage("--repeat >= 1 and --threads >= 0 expected");
    return o;
}

// Simulation::run has no step limit; this observer ends the run by throwing after
// `limit` steps, and the driver collects the statistics itself.
struct StepLimitReached {};
class StepLimit : public StepObserver {
  public:
    explicit StepLimit(std::uint64_t limit) : limit_(limit) {}
    void on_step(const SimulationView& v) override {
        t = v.t;
        if (v.step >= limit_) throw StepLimitReached{};
    }
    double t = 0.0;

  private:
    std::uint64_t limit_;
};

struct Outcome {
    double wall = 0.0, cpu = 0.0, construct = 0.0, t = 0.0, mass_error = 0.0, outflow = 0.0;
    std::uint64_t steps = 0, updates = 0, band_updates = 0;
    std::string end;
};

// One run of the production time loop (Simulation::run: CFL step, Strang step, state
// check, end-of-run scans), limited to step_limit steps when step_limit > 0. The
// initial state moves into the Simulation, as in `avalanche-hazard run`: a copy kept
// here would add 24 bytes per cell to the peak memory the benchmark reports.
Outcome run_once(Scene& s, long step_limit) {
    Outcome o;
    const double v0 = total_volume(s.initial, s.grid, s.released);
    const auto t0 = Clock::now();
    Simulation sim(s.grid, s.terrain, s.material, s.numerics, std::move(s.initial), s.h_min, s.released);
    o.construct = seconds_since(t0);
    StepLimit limit(step_limit > 0 ? static_cast<std::uint64_t>(step_limit) : UINT64_MAX);
    sim.add_observer(&limit);
    const auto t1 = Clock::now();
    const double cpu1 = process_cpu_seconds();
    try {
        const RunStatistics st = sim.run();
        o.wall = seconds_since(t1);
        o.cpu = process_cpu_seconds() - cpu1;
        o.t = st.simulated_time;
        o.steps = st.steps;
        o.end = to_string(st.end_reason);
        o.mass_error = st.relative_mass_error();
    } catch (const StepLimitReached&) {
        o.wall = seconds_since(t1);
        o.cpu = process_cpu_seconds() - cpu1;
        o.t = limit.t;
        o.steps = static_cast<std::uint64_t>(step_limit);
        o.end = "step_limit";
        o.mass_error =
            (total_volume(sim.state(), s.grid, sim.stepper().active_box()) + sim.stepper().outflow_volume() - v0) /
            v0;
    }
    o.updates = sim.stepper().cell_updates();
    o.band_updates = sim.stepper().band_cell_updates();
    o.outflow = sim.stepper().outflow_volume();
    return o;
}

// A scene of the case, with the splitting --splitting asks for.
template <class Build>
Scene make_scene(Build build, const Options& opt) {
    Scene s = build();
    if (opt.splitting) s.numerics.splitting = *opt.splitting;
    return s;
}

// The run's own data at its peak: one more run of the case, after the timed ones, from
// a resident set that already holds the code it executes. The timed runs made the
// program's and its libraries' pages resident as they first ran them (1.2-1.3 MB on case
// (b), whose first run's peak counts them); the heap's free pages go back to the system
// first, and glibc's mmap threshold is set to its initial value, which the frees of the
// timed runs raised, so that the grids are allocated as in a process's first run. The
// threads' stacks, made by the timed runs, are not in it. 0 where /proc cannot say.
template <class Build>
double data_peak_bytes(Build build, long step_limit, const Options& opt) {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 128 * 1024);
    malloc_trim(0);
#endif
    if (!reset_vm_hwm()) return 0.0;
    const double start = static_cast<double>(test::resident_bytes());
    Scene s = make_scene(build, opt);
    (void)run_once(s, step_limit);
    const double peak = vm_hwm_bytes();
    return start > 0.0 && peak > start ? peak - start : 0.0;
}

// Each repetition builds its scene afresh (its initial state is consumed by the run);
// the setup time is the first one's.
template <class Build>
RunRecord timed_case(const std::string& case_id, Build build, long step_limit, const Options& opt) {
    RunRecord r;
    r.case_id = case_id;
#ifdef _OPENMP
    r.threads = omp_get_max_threads();
#endif
    r.load_average = load_average_1min();
    r.start_rss_bytes = static_cast<double>(std::max(0LL, test::resident_bytes()));
    for (int k = 0; k < opt.repeat; ++k) {
        const auto t0 = Clock::now();
        Scene s = make_scene(build, opt);
        const double scene_seconds = seconds_since(t0);
        r.scene = s.name;
        r.scheme = to_string(s.numerics.scheme);
        r.splitting = enum_name(kSplittingNames, s.numerics.splitting);
        r.nx = s.grid.nx;
        r.ny = s.grid.ny;
        const Outcome o = run_once(s, step_limit);
        if (k == 0) {
            r.setup_seconds = scene_seconds + o.construct;
            r.dem_seconds = s.dem_seconds;
        }
        r.wall_seconds.push_back(o.wall);
        r.cpu_seconds.push_back(o.cpu);
        r.simulated_time = o.t;
        r.steps = o.steps;
        r.cell_updates = o.updates;
        r.band_cell_updates = o.band_updates;
        r.end_reason = o.end;
        r.relative_mass_error = o.mass_error;
        r.outflow_volume = o.outflow;
        // The first run's peak: later repetitions read higher (case (d) 130.2 -> 138.5
        // B/cell with --repeat 3), because glibc raises its mmap threshold when the
        // first run frees its grids, so the next run's grids come from the heap, which
        // is not given back between runs (with MALLOC_MMAP_THRESHOLD_=131072, which
        // fixes the threshold, three repetitions peak at 129.8).
        if (k == 0) r.peak_rss_bytes = peak_rss_bytes();
    }
    if (opt.data_peak) r.data_peak_bytes = data_peak_bytes(build, step_limit, opt);
    return r;
}

void report(const RunRecord& r, const Options& opt) {
    print(r);
    if (!opt.json.empty()) append_json(r, opt.json);
}

// (d): the same release and simulated time on a 200 x 200 crop and on the full
// 2000 x 2000 DEM; the crop runs first so that each peak RSS is its own.
void case_d(Scheme scheme, const Options& opt) {
    const ValleyRelease release{0.0, 6000.0, 50.0, 10.0};
    constexpr double t_end = 20.0;  // the flow stays well inside the crop (checked: no outflow)
    RunRecord crop = timed_case(
        "d_crop", [&] { return valley(200, 200, 10.0, -1000.0, 4500.0, release, scheme, t_end); },
        -1, opt);
    report(crop, opt);
    RunRecord full = timed_case(
        "d_full",
        [&] { return valley(2000, 2000, 10.0, -10000.0, -6000.0, release, scheme, t_end); }, -1,
        opt);
    std::ostringstream note;
    note << "wall ratio full/crop = " << full.best_wall() / crop.best_wall()
         << " (target <= 3); with setup "
         << (full.best_wall() + full.setup_seconds) / (crop.best_wall() + crop.setup_seconds)
         << "; with the setup but not the DEM's sampling (a run reads its DEM from a file) "
         << (full.best_wall() + full.setup_seconds - full.dem_seconds) /
                (crop.best_wall() + crop.setup_seconds - crop.dem_seconds)
         << "; cell updates full/crop = "
         << static_cast<double>(full.cell_updates) / static_cast<double>(crop.cell_updates);
    full.note = note.str();
    report(full, opt);
}

void run_job(char which, Scheme scheme, const Options& opt) {
    switch (which) {
        case 'a':
            report(timed_case(
                       "a", [&] { return tilted_plane(1000, 5.0, 30.0, 1.0, scheme); },
                       opt.steps > 0 ? opt.steps : 50, opt),
                   opt);
            break;
        case 'b':
            report(timed_case(
                       "b", [&] { return paper_chute(0.2, scheme); }, opt.steps, opt),
                   opt);
            break;
        case 'c':
            report(timed_case(
                       "c",
                       [&] {
                           return valley(400, 1000, 10.0, -2000.0, 0.0, ValleyRelease{}, scheme,
                                         150.0);
                       },
                       opt.steps, opt),
                   opt);
            break;
        case 'd':
            case_d(scheme, opt);
            break;
        default:
            break;
    }
}

}  // namespace

int main(int argc, char** argv) {
    const Options opt = parse(argc, argv);
    const std::string cases = opt.which == "all" ? "abcd" : opt.which;
    std::vector<Scheme> schemes;
    if (opt.scheme != "godunov") schemes.push_back(Scheme::waf);
    if (opt.scheme != "waf") schemes.push_back(Scheme::godunov);
    int failures = 0;
    for (char c : cases) {
        for (Scheme s : schemes) {
            // One child per job: ru_maxrss is then the job's own peak. The parent
            // never enters an OpenMP region, so the child's runtime starts clean.
            std::cout.flush();
            const pid_t pid = fork();
            if (pid < 0) {
                std::cerr << "bench_runs: fork failed\n";
                return 1;
            }
            if (pid == 0) {
                int code = 0;
                try {
#ifdef _OPENMP
                    if (opt.threads > 0) omp_set_num_threads(opt.threads);
#endif
                    run_job(c, s, opt);
                } catch (const std::exception& e) {
                    std::cerr << "bench_runs: case " << c << " (" << to_string(s)
                              << "): " << e.what() << "\n";
                    code = 1;
                }
                std::cout.flush();
                _exit(code);
            }
            int status = 0;
            waitpid(pid, &status, 0);
            if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) ++failures;
        }
    }
    return failures == 0 ? 0 : 1;
}
