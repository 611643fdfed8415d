#pragma once
// One measured run of bench_runs: what is printed and what goes into the JSON file.
#include <cstdint>
#include <string>
#include <vector>

namespace avalanche::bench {

struct RunRecord {
    std::string case_id;  // "a", "b", "c", "d_crop", "d_full"
    std::string scene;    // scene name
    std::string scheme;   // "waf" or "godunov"
    std::string splitting = "lsl";  // "lsl" (two advections per step) or "sls" (one)
    int threads = 1;      // omp_get_max_threads() during the run
    int nx = 0, ny = 0;
    double setup_seconds = 0.0;        // terrain, release and Simulation construction
    double dem_seconds = 0.0;          // of setup_seconds: sampling the DEM (Scene::dem_seconds)
    std::vector<double> wall_seconds;  // of Simulation::run, one per repetition
    // CPU time of the process (all threads) during each Simulation::run. On one thread
    // cpu / wall below 1 means the run was descheduled: the machine was busy and the
    // wall time overstates the cost (a VM's stolen time is not the process's CPU time).
    // Near 1 does not prove a quiet machine: work on the sibling hardware thread slows
    // a run without taking its CPU time (docs/performance.md, bench_divider).
    std::vector<double> cpu_seconds;
    double load_average = -1.0;  // 1-minute load average before the first repetition
    double simulated_time = 0.0;       // s
    std::uint64_t steps = 0;
    std::uint64_t cell_updates = 0;  // active-box cells x steps (RunStatistics)
    // Of those, the cells the bands computed (Stepper::band_cell_updates): the rest are
    // empty cells and settled films, which a step gives back without computing them.
    std::uint64_t band_cell_updates = 0;
    std::string end_reason;
    double relative_mass_error = 0.0;
    double outflow_volume = 0.0;  // m^3 through open edges (case d: must be 0 on the crop)
    double peak_rss_bytes = 0.0;  // getrusage ru_maxrss of this process (one case per process)
    // The resident set of the case's process before its first scene is built (0 where
    // unknown): the program, its libraries and runtime, which a small grid's bytes per
    // cell would otherwise carry (1.6 MB on the project machine; case (b) peaks at 6-9 MB).
    double start_rss_bytes = 0.0;
    // The run's own data at its peak (0 where unknown, or with --data-peak off): one
    // more run of the case after the timed ones, its peak resident set above the
    // resident set before its scene is built (bench_runs.cpp, data_peak_bytes). The
    // code the run executes, which the timed runs made resident, is not in it: on case
    // (b) a run makes 1.2-1.3 MB of the program's and its libraries' code resident, 21 B
    // per cell of its 60 000 cells.
    double data_peak_bytes = 0.0;
    std::string note;             // e.g. the ratio of case (d)

    [[nodiscard]] double best_wall() const;
    [[nodiscard]] double cell_updates_per_second() const;  // with the best wall time
    [[nodiscard]] double bytes_per_cell() const;           // peak RSS / grid cells
    [[nodiscard]] double scene_bytes_per_cell() const;     // (peak - start RSS) / grid cells
    [[nodiscard]] double data_bytes_per_cell() const;      // data_peak_bytes / grid cells
};

// Peak resident set of the calling process (bytes).
double peak_rss_bytes();
// Resets the peak resident set of /proc/self/status (VmHWM) to the current resident set
// (Linux: /proc/self/clear_refs); false where it cannot.
bool reset_vm_hwm();
// VmHWM of /proc/self/status (bytes), or -1 where it cannot be read.
double vm_hwm_bytes();
// CPU time of the calling process, all threads (s).
double process_cpu_seconds();
// The system's 1-minute load average, or -1 where it cannot be read.
double load_average_1min();

// One human-readable line block on stdout.
void print(const RunRecord& r);

// Appends the record as one JSON object on one line (JSON Lines), so that runs of
// several processes can share a file without rewriting it.
void append_json(const RunRecord& r, const std::string& path);

}  // namespace avalanche::bench
