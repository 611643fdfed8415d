#include "avalanche/io/summary_writer.hpp"

#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/effective_config.hpp"

namespace avalanche {

nlohmann::json make_summary(const SummaryInputs& in) {
    const RunStatistics& st = in.stats;
    nlohmann::json s;
    s["software_version"] = software_version();
    s["source_hash"] = source_hash();
    s["command_line"] = in.command_line;
    s["config_hash"] = in.config_hash;
    s["end_reason"] = to_string(st.end_reason);
    // An interrupted run's products hold the flow so far, not the run's result.
    s["complete"] = st.end_reason != EndReason::interrupted;
    s["simulated_time_s"] = st.simulated_time;
    s["steps"] = st.steps;
    s["wall_s"] = st.wall_seconds;
    s["h_min_m"] = in.h_min;
    s["frame"] = in.frame == Frame::chute ? "chute" : "dem";
    s["grid"] = {
        {"nx", in.grid.nx}, {"ny", in.grid.ny}, {"dx_m", in.grid.dx}, {"dy_m", in.grid.dy}};
    s["performance"] = {{"cell_updates", st.cell_updates},
                        {"cell_updates_per_s", st.cell_updates_per_second()},
                        {"threads", st.threads}};
    s["volume"] = {{"released_m3", st.released_volume},
                   {"final_m3", st.final_volume},
                   {"outflow_m3", st.outflow_volume},
                   {"relative_error", st.relative_mass_error()}};
    s["max_kinetic_energy_m5_per_s2"] = st.max_kinetic_energy;
    s["final_kinetic_energy_m5_per_s2"] = st.final_kinetic_energy;
    s["final_kinetic_energy_fraction"] = st.final_kinetic_energy_fraction();
    s["outputs"] = {{"results", in.results_file}, {"snapshots", in.snapshots}};
    s["parameters"] = in.config;
    return s;
}

void write_summary(const std::string& path, const SummaryInputs& in) {
    write_file_atomically(path, make_summary(in).dump(2) + "\n");
}

}  // namespace avalanche
