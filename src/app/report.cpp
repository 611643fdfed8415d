// DIR/report.md: one page a planner can read without us (issue: GIS pipeline, item 5).
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "avalanche/app/products.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/effective_config.hpp"

namespace avalanche {

namespace {
std::string fixed(double v, int digits) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}
}  // namespace

void write_report(const std::string& dir, const ProductInputs& in, const std::vector<std::string>& files) {
    const RunStatistics& st = in.stats;
    const RunoutMetrics& r = in.runout;
    const OutputParams& out = in.scenario.output;
    std::ostringstream m;
    m << "# Avalanche hazard simulation report\n\n";
    if (st.end_reason == EndReason::interrupted)
        m << "> **INCOMPLETE**: the run was interrupted at t = " << fixed(st.simulated_time, 2)
          << " s; the maps cover only the flow up to then. Continue it with "
             "`avalanche-hazard run --resume` on this folder.\n\n";
    // Before anything a planner might draw a zone from (run_caveats.hpp).
    if (!in.caveats.empty()) {
        m << "> **Caveats of this run: the maps may understate the hazard.**\n";
        for (const auto& c : in.caveats) m << ">\n> - " << c.message << "\n";
        m << "\n";
    }
    m << "Software: avalanche-hazard " << software_version() << " (sources `" << source_hash()
      << "`). Configuration hash `" << in.config_hash << "`.\n\nCommand:\n\n```\n"
      << in.command_line << "\n```\n\n";
    m << "## What was simulated\n\n" << in.scene.description << ".\n\n";
    for (const auto& note : in.scene.input_notes) m << "- " << note << "\n";
    m << "\nMaterial: internal friction angle " << in.scenario.material.phi_deg << " deg, bed friction angle "
      << in.scenario.material.delta_deg << " deg, density " << in.scenario.material.density
      << " kg/m3. Released volume " << fixed(st.released_volume, 1) << " m3.\n\n";

    m << "## Results in brief\n\n| quantity | value |\n|---|---|\n";
    m << "| runout length (horizontal, top of release to farthest reached point) | " << fixed(r.runout_length_m, 1)
      << " m |\n";
    m << "| fall height | " << fixed(r.fall_height_m, 1) << " m |\n";
    m << "| travel angle (fall height / runout length) | " << fixed(r.travel_angle_deg, 1) << " deg |\n";
    m << "| runout efficiency (runout length / fall height) | " << fixed(r.runout_efficiency, 2) << " |\n";
    m << "| affected area (depth >= " << out.h_threshold << " m at some time) | " << fixed(r.affected_area_m2, 0)
      << " m2 |\n";
    m << "| maximum depth / speed / impact pressure | " << fixed(r.max_depth_m, 2) << " m / "
      << fixed(r.max_velocity_ms, 1) << " m/s / " << fixed(r.max_pressure_kpa, 1) << " kPa |\n";
    m << "| deposited volume (thicker than " << out.h_threshold << " m) | " << fixed(r.deposit_volume_m3, 1)
      << " m3 |\n";
    m << "| duration simulated, end of run | " << fixed(st.simulated_time, 1) << " s, " << to_string(st.end_reason)
      << " (kinetic energy at the end " << std::scientific << std::setprecision(1)
      << st.final_kinetic_energy_fraction() << std::defaultfloat << " of its maximum) |\n";
    m << "| mass balance: released = final + outflow | " << fixed(st.released_volume, 3) << " = "
      << fixed(st.final_volume, 3) << " + " << fixed(st.outflow_volume, 3) << " m3 (relative error "
      << std::scientific << std::setprecision(1) << st.relative_mass_error() << std::defaultfloat << ") |\n";
    m << "| computation | " << fixed(st.wall_seconds, 1) << " s wall, " << std::setprecision(3)
      << st.cell_updates_per_second() << " cell updates/s on " << st.threads << " threads |\n\n";

    m << "## Hazard classes\n\nEach cell that the flow reached (depth at least " << out.h_threshold
      << " m) gets a class from the highest impact pressure it felt (pressure = density x speed squared):\n\n";
    m << "- **high** (red): " << out.pressure_high_kpa
      << " kPa or more: buildings can be destroyed; people are in danger inside buildings.\n";
    m << "- **medium** (blue): from " << out.pressure_low_kpa << " to " << out.pressure_high_kpa
      << " kPa: people are in danger outside buildings; buildings can be damaged.\n";
    m << "- **low** (yellow): below " << out.pressure_low_kpa
      << " kPa: reached by the flow with little pressure; danger is low but not absent.\n";
    m << "- not reached: outside the coloured area.\n\n";
    m << "These limits follow Alpine avalanche zoning practice; they are parameters of the run "
         "(`output.pressure_low_kpa`, `output.pressure_high_kpa`). The maps are one scenario: the friction "
         "angles are uncertain, so compare several (batch mode) before drawing a line.\n\n";

    m << "## Maps\n\nEach map is a GeoTIFF (open it in QGIS; the `.qml` style beside it colours it). "
         "Thicknesses are measured perpendicular to the slope.";
    if (!in.scene.outside_data.empty())
        m << " " << kNoTerrainDataNote;
    m << "\n\n";
    for (const auto& f : files) {
        if (f.size() < 4 || f.substr(f.size() - 4) != ".png") continue;
        const std::string base = f.substr(0, f.size() - 4);
        m << "### " << base << "\n\n![" << base << "](" << f << ")\n\n";
    }
    if (in.probes && !in.probes->points().empty()) {
        m << "## Monitoring points\n\n| point | first arrival (s) | max depth (m) | max speed (m/s) | max pressure "
             "(kPa) |\n|---|---|---|---|---|\n";
        for (std::size_t p = 0; p < in.probes->points().size(); ++p) {
            const auto& loc = in.probes->points()[p];
            const std::size_t k = static_cast<std::size_t>(loc.j) * in.scene.grid.nx + loc.i;
            const double a = in.maps.arrival_time(k);
            m << "| " << loc.name << " | " << (a == HazardMaps::kNotReached ? std::string("not reached") : fixed(a, 1))
              << " | " << fixed(in.maps.max_depth()[k], 2) << " | " << fixed(in.maps.max_speed()[k], 1) << " | "
              << fixed(in.maps.max_pressure(k), 1) << " |\n";
        }
        m << "\nTime series: `monitoring.csv`, `monitoring.h5` (speeds and pressures while the flow "
             "is at least "
          << out.h_threshold << " m deep, as in the maps).\n\n";
    }
    m << "## Files\n\n";
    for (const auto& f : files) m << "- `" << f << "`\n";
    m << "- `results.h5`: snapshots of depth and velocity; `summary.json`: every number above.\n";
    write_file_atomically((std::filesystem::path(dir) / "report.md").string(), m.str());
}

}  // namespace avalanche
