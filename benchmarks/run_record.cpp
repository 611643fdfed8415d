#include "run_record.hpp"

#include <sys/resource.h>

#include <cstdlib>
#include <ctime>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>

namespace avalanche::bench {

double RunRecord::best_wall() const {
    return wall_seconds.empty() ? 0.0 : *std::min_element(wall_seconds.begin(), wall_seconds.end());
}

double RunRecord::cell_updates_per_second() const {
    const double w = best_wall();
    return w > 0.0 ? static_cast<double>(cell_updates) / w : 0.0;
}

namespace {
// The share of the cell updates the bands computed, in per cent.
double band_share(const RunRecord& r) {
    return r.cell_updates > 0 ? 100.0 * static_cast<double>(r.band_cell_updates) /
                                    static_cast<double>(r.cell_updates)
                              : 0.0;
}
}  // namespace

double RunRecord::bytes_per_cell() const {
    const double cells = static_cast<double>(nx) * ny;
    return cells > 0.0 ? peak_rss_bytes / cells : 0.0;
}

double RunRecord::scene_bytes_per_cell() const {
    const double cells = static_cast<double>(nx) * ny;
    return cells > 0.0 ? (peak_rss_bytes - start_rss_bytes) / cells : 0.0;
}

double RunRecord::data_bytes_per_cell() const {
    const double cells = static_cast<double>(nx) * ny;
    return cells > 0.0 ? data_peak_bytes / cells : 0.0;
}

bool reset_vm_hwm() {
    std::ofstream f("/proc/self/clear_refs");
    f << "5";  // "reset the peak resident set size to the current one" (proc(5))
    f.flush();
    return static_cast<bool>(f);
}

double vm_hwm_bytes() {
    std::ifstream f("/proc/self/status");
    std::string key;
    while (f >> key) {
        if (key == "VmHWM:") {
            double kib = -1.0;
            return f >> kib ? kib * 1024.0 : -1.0;
        }
        f.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return -1.0;
}

double peak_rss_bytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) * 1024.0;  // Linux reports kilobytes
}

double process_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double load_average_1min() {
    double load[1] = {0.0};
    return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

namespace {
// CPU time of the repetition with the best wall time, over that wall time.
double cpu_per_wall(const RunRecord& r) {
    if (r.wall_seconds.empty() || r.cpu_seconds.size() != r.wall_seconds.size()) return 0.0;
    const auto best = std::min_element(r.wall_seconds.begin(), r.wall_seconds.end());
    const std::size_t k = static_cast<std::size_t>(best - r.wall_seconds.begin());
    return *best > 0.0 ? r.cpu_seconds[k] / *best : 0.0;
}
}  // namespace

void print(const RunRecord& r) {
    std::ostringstream walls;
    for (std::size_t k = 0; k < r.wall_seconds.size(); ++k)
        walls << (k ? ", " : "") << r.wall_seconds[k];
    std::cout << std::setprecision(4) << "case " << r.case_id << " (" << r.scene << ", " << r.scheme
              << ", " << r.splitting << ", " << r.threads << " thread" << (r.threads > 1 ? "s" : "")
              << "), grid " << r.nx << " x " << r.ny << "\n  wall " << r.best_wall()
              << " s (best of [" << walls.str() << "]), setup " << r.setup_seconds
              << " s (of which sampling the DEM " << r.dem_seconds << " s)\n  simulated "
              << r.simulated_time << " s in " << r.steps
              << " steps, end: " << r.end_reason << "\n  cell updates "
              << static_cast<double>(r.cell_updates) << ", " << r.cell_updates_per_second() / 1e6
              << " M/s (of which the bands computed "
              << static_cast<double>(r.band_cell_updates) << ", "
              << band_share(r) << " %)\n  peak memory " << r.peak_rss_bytes / 1048576.0
              << " MiB = " << r.bytes_per_cell() << " B/cell (" << r.scene_bytes_per_cell()
              << " B/cell above the " << r.start_rss_bytes / 1048576.0
              << " MiB resident before the scene)\n  the run's data at its peak "
              << r.data_peak_bytes / 1048576.0 << " MiB = " << r.data_bytes_per_cell()
              << " B/cell (a run after the timed ones, its code resident before)\n  mass error "
              << r.relative_mass_error
              << ", outflow " << r.outflow_volume << " m^3\n  cpu / wall of the best run "
              << cpu_per_wall(r) << " (threads " << r.threads << "), load average before "
              << r.load_average << "\n";
    if (!r.note.empty()) std::cout << "  " << r.note << "\n";
    std::cout << std::flush;
}

namespace {
std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}
}  // namespace

void append_json(const RunRecord& r, const std::string& path) {
    std::ostringstream o;
    o << std::setprecision(10) << "{\"case\": " << quoted(r.case_id)
      << ", \"scene\": " << quoted(r.scene) << ", \"scheme\": " << quoted(r.scheme)
      << ", \"splitting\": " << quoted(r.splitting)
      << ", \"threads\": " << r.threads << ", \"nx\": " << r.nx << ", \"ny\": " << r.ny
      << ", \"setup_seconds\": " << r.setup_seconds << ", \"dem_seconds\": " << r.dem_seconds
      << ", \"wall_seconds\": [";
    for (std::size_t k = 0; k < r.wall_seconds.size(); ++k)
        o << (k ? ", " : "") << r.wall_seconds[k];
    o << "], \"cpu_seconds\": [";
    for (std::size_t k = 0; k < r.cpu_seconds.size(); ++k)
        o << (k ? ", " : "") << r.cpu_seconds[k];
    o << "], \"load_average_1min\": " << r.load_average
      << ", \"best_wall_seconds\": " << r.best_wall()
      << ", \"simulated_time\": " << r.simulated_time << ", \"steps\": " << r.steps
      << ", \"cell_updates\": " << r.cell_updates
      << ", \"cell_updates_per_second\": " << r.cell_updates_per_second()
      << ", \"band_cell_updates\": " << r.band_cell_updates
      << ", \"peak_rss_bytes\": " << r.peak_rss_bytes
      << ", \"bytes_per_cell\": " << r.bytes_per_cell()
      << ", \"start_rss_bytes\": " << r.start_rss_bytes
      << ", \"scene_bytes_per_cell\": " << r.scene_bytes_per_cell()
      << ", \"data_peak_bytes\": " << r.data_peak_bytes
      << ", \"data_bytes_per_cell\": " << r.data_bytes_per_cell()
      << ", \"end_reason\": " << quoted(r.end_reason)
      << ", \"relative_mass_error\": " << r.relative_mass_error
      << ", \"outflow_volume\": " << r.outflow_volume << ", \"note\": " << quoted(r.note) << "}\n";
    std::ofstream f(path, std::ios::app);
    f << o.str();
    if (!f) std::cerr << "bench_runs: cannot append to " << path << "\n";
}

}  // namespace avalanche::bench
