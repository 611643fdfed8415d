// Monitoring points, run, parameters and provenance sections of a run's report.html.
#include "report_html_sections.hpp"

#include <spdlog/spdlog.h>

#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/io/html_text.hpp"
#include "avalanche/io/sha256.hpp"
#include "avalanche/io/svg_plot.hpp"
#include "report_html_parts.hpp"

namespace avalanche::detail {

namespace {

std::string row(const std::string& label, const std::string& value_html,
                const std::string& units = "") {
    return "<tr><th>" + html_escape(label) + "</th>" + value_html + "<td>" + html_escape(units) +
           "</td></tr>\n";
}

std::string end_reason_words(const std::string& reason) {
    if (reason == "end_time") return "the run reached its end time t_end";
    if (reason == "stopped_at_rest") return "the flow came to rest before t_end";
    if (reason == "stopped_kinetic_energy")
        return "the kinetic energy fell below numerics.stop_ke_fraction of its peak for "
               "numerics.stop_duration: the flow had practically stopped";
    if (reason == "no_material") return "all material left the grid";
    if (reason == "interrupted") return "the run was interrupted: the maps are incomplete";
    return reason;
}

// One row per leaf of the configuration; array elements are marked one by one.
void flatten(const nlohmann::json& summary, const nlohmann::json& node, const std::string& key,
             std::ostringstream& out) {
    if (node.is_object()) {
        for (const auto& [name, value] : node.items())
            flatten(summary, value, key + "." + name, out);
        return;
    }
    // The row label without "parameters.<group>.".
    const auto second_dot = key.find('.', key.find('.') + 1);
    const std::string label = second_dot == std::string::npos ? "" : key.substr(second_dot + 1);
    out << "<tr><td><code>" << html_escape(label) << "</code></td><td>";
    if (node.is_array())
        for (std::size_t k = 0; k < node.size(); ++k)
            out << (k ? ", " : "") << keyed(summary, key + "." + std::to_string(k));
    else
        out << keyed(summary, key);
    out << "</td></tr>\n";
}

}  // namespace

std::string monitoring_section(const ProductInputs& in, const nlohmann::json& summary) {
    if (!in.probes || in.probes->points().empty() || !summary.contains("monitoring_points"))
        return "";
    std::ostringstream s;
    s << "<section id=\"monitoring\"><h2>Monitoring points</h2>\n<p>What the flow did at "
         "chosen places (white dots on the maps). Depth is measured perpendicular to the slope; "
         "the pressure is the impact pressure on an obstacle standing across the flow. As in "
         "the maps, speed and pressure count only while the flow is at least "
      << format_number(in.scenario.output.h_threshold)
      << " m deep: a thinner layer is the numerical film a flow leaves, not flowing "
         "material.</p>\n"
         "<table><tr><th>point</th><th class=\"n\">x (m)</th><th class=\"n\">y (m)</th><th "
         "class=\"n\">first arrival (s)</th><th class=\"n\">max depth (m)</th><th "
         "class=\"n\">max speed (m/s)</th><th class=\"n\">max pressure (kPa)</th></tr>\n";
    const auto& points = summary["monitoring_points"];
    for (std::size_t p = 0; p < points.size(); ++p) {
        const std::string k = "monitoring_points." + std::to_string(p) + ".";
        s << "<tr>" << keyed(summary, k + "name", "td");
        for (const char* field : {"x", "y"}) s << keyed(summary, k + field, "td");
        s << keyed(summary, k + "arrival_time_s", "td", "not reached");
        for (const char* field : {"max_depth_m", "max_velocity_ms", "max_pressure_kpa"})
            s << keyed(summary, k + field, "td");
        s << "</tr>\n";
    }
    s << "</table>\n<div class=\"plots\">\n";
    struct Quantity {
        const char* title;
        const char* y_label;
        double ProbeSample::*member;
    };
    for (const Quantity& q :
         {Quantity{"Flow depth at the monitoring points", "depth, bed-normal (m)", &ProbeSample::h},
          Quantity{"Speed at the monitoring points", "speed (m/s)", &ProbeSample::speed},
          Quantity{"Impact pressure at the monitoring points", "pressure (kPa)",
                   &ProbeSample::pressure}}) {
        LinePlot plot{q.title, "time (s)", q.y_label, {}};
        for (std::size_t p = 0; p < in.probes->points().size(); ++p) {
            PlotSeries series{in.probes->points()[p].name, {}, {}};
            for (const ProbeSample& sample : in.probes->series()[p]) {
                series.x.push_back(sample.t);
                series.y.push_back(sample.*q.member);
            }
            plot.series.push_back(std::move(series));
        }
        s << inline_svg(svg_line_plot(plot));
    }
    s << "</div>\n<p class=\"note\">All samples: <code>monitoring.csv</code>, "
         "<code>monitoring.h5</code>.</p></section>\n";
    return s.str();
}

std::string run_section(const nlohmann::json& summary) {
    std::ostringstream s;
    const nlohmann::json* reason = json_at(summary, "end_reason");
    s << "<section id=\"run\"><h2>How the run ended, mass balance, computation</h2>\n<p>End: "
      << keyed(summary, "end_reason") << " ("
      << html_escape(end_reason_words(reason ? json_text(*reason) : "")) << ") after "
      << keyed(summary, "simulated_time_s") << " s of simulated time.</p>\n"
      << "<p>Mass balance: the volume released must equal the volume left on the grid plus "
         "the volume that flowed out of it (over the grid edge or into cells outside the "
         "DEM's data). The relative error measures how well the solver conserved mass.</p>\n"
      << "<table>\n"
      << row("released volume", keyed(summary, "volume.released_m3", "td"), "m³")
      << row("volume on the grid at the end", keyed(summary, "volume.final_m3", "td"), "m³")
      << row("outflow", keyed(summary, "volume.outflow_m3", "td"), "m³")
      << row("relative error (released - final - outflow) / released",
             keyed(summary, "volume.relative_error", "td"))
      << row("time steps", keyed(summary, "steps", "td"))
      << row("wall-clock time", keyed(summary, "wall_s", "td"), "s")
      << row("throughput", keyed(summary, "performance.cell_updates_per_s", "td"), "cell updates/s")
      << row("threads", keyed(summary, "performance.threads", "td"))
      << row("grid",
             "<td>" + keyed(summary, "grid.nx") + " x " + keyed(summary, "grid.ny") + "</td>",
             "cells")
      << row("cell size", keyed(summary, "grid.dx_m", "td"), "m")
      << row("thin-layer depth h_min", keyed(summary, "h_min_m", "td"), "m")
      << "</table></section>\n";
    return s.str();
}

std::string parameters_section(const nlohmann::json& summary) {
    std::ostringstream s;
    s << "<section id=\"parameters\"><h2>Parameters</h2>\n<p>The effective configuration "
         "(built-in defaults, then the scenario file, then the command-line flags), as in "
         "<code>summary.json</code> <code>parameters</code>; its hash "
      << keyed(summary, "config_hash", "code") << " is written into every map.</p>\n<table>\n";
    if (const nlohmann::json* p = json_at(summary, "parameters"); p && p->is_object())
        for (const auto& [group, values] : p->items()) {
            s << "<tr><th colspan=\"2\">[" << html_escape(group) << "]</th></tr>\n";
            flatten(summary, values, "parameters." + group, s);
        }
    s << "</table></section>\n";
    return s.str();
}

std::string provenance_section(const nlohmann::json& summary) {
    std::ostringstream s;
    s << "<section id=\"provenance\"><h2>Inputs, software and command</h2>\n";
    const nlohmann::json* inputs = json_at(summary, "inputs");
    if (inputs && inputs->is_array() && !inputs->empty()) {
        s << "<p>Input files and their SHA-256 checksums (compare with <code>sha256sum "
             "FILE</code> to check that a file is the one these maps were computed from):</p>\n"
             "<table><tr><th>file</th><th>SHA-256</th></tr>\n";
        for (std::size_t k = 0; k < inputs->size(); ++k) {
            const std::string path = json_text((*inputs)[k]);
            std::string digest;
            try {
                digest = sha256_file_hex(path);
            } catch (const Error& e) {
                // The run is done: a checksum that cannot be computed is reported, not fatal.
                spdlog::warn("report.html: {}", e.what());
                digest = "unreadable";
            }
            s << "<tr>" << keyed(summary, "inputs." + std::to_string(k), "td")
              << "<td class=\"hash sha256\" data-file=\"" << html_escape(path) << "\">"
              << html_escape(digest) << "</td></tr>\n";
        }
        s << "</table>\n";
    } else {
        s << "<p>No input files: the terrain and release are built from the scenario's "
             "parameters.</p>\n";
    }
    s << "<p>Software: avalanche-hazard " << keyed(summary, "software_version") << " (sources "
      << keyed(summary, "source_hash", "code")
      << "). Command line (run it again from the same folder to reproduce these results):</p>\n"
      << keyed(summary, "command_line", "pre") << "</section>\n";
    return s.str();
}

}  // namespace avalanche::detail
