// DIR/report.html of a run (issue 7 part 4, "the planner's report"): the results in plain
// words, the hazard classes explained, the maps with legend, scale bar and north arrow, the
// monitoring series, the run's numbers and its provenance, in one offline file.
#include "avalanche/app/report_html.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "avalanche/app/report_html_map.hpp"
#include "avalanche/gis/geo_grid.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/html_text.hpp"
#include "report_html_parts.hpp"
#include "report_html_sections.hpp"

namespace avalanche {

namespace {

using detail::keyed;

// The maps in the report, with the ramps of their quick-looks. These are the ramps that
// write_products (products.cpp) draws <map>.png with; keep the two lists in step.
std::vector<MapFigure> map_figures(const ProductInputs& in) {
    const OutputParams& out = in.scenario.output;
    return {
        {"max_depth", "Maximum flow depth",
         "The largest thickness of the flowing material at each place during the whole run, "
         "measured perpendicular to the slope.",
         "", gis::depth_ramp(), "flow depth, m (bed-normal)"},
        {"max_velocity", "Maximum speed", "The highest speed of the flow at each place.", "",
         gis::velocity_ramp(), "speed, m/s"},
        {"max_pressure", "Maximum impact pressure",
         "The highest pressure the flow would exert on an obstacle standing across it "
         "(density x speed²). The class limits of the hazard map are two of its breaks.",
         "", gis::pressure_ramp({1.0, out.pressure_low_kpa, 10.0, out.pressure_high_kpa, 100.0}),
         "impact pressure, kPa"},
        {"hazard_class", "Hazard classes",
         "Intensity classes from the maximum impact pressure (see 'Hazard classes' above).", "",
         gis::hazard_class_palette(
             {"not reached", "low: below " + format_number(out.pressure_low_kpa) + " kPa",
              "medium: " + format_number(out.pressure_low_kpa) + " - " +
                  format_number(out.pressure_high_kpa) + " kPa",
              "high: " + format_number(out.pressure_high_kpa) + " kPa or more"}),
         "hazard class (maximum impact pressure)"},
        {"arrival_time", "Arrival time",
         "When the flow first reached each place, in seconds after the release: the time "
         "left to react.",
         "", gis::arrival_time_ramp(std::max(in.stats.simulated_time, 1e-9)), "arrival time, s"},
        {"deposit_thickness", "Deposit",
         "Where the material lies at the end of the run, and how thick (perpendicular to the "
         "slope).",
         "", gis::depth_ramp(), "deposit thickness, m (bed-normal)"},
    };
}

std::string header(const ProductInputs& in, const nlohmann::json& summary) {
    std::ostringstream s;
    s << "<header><h1>Avalanche hazard simulation report</h1>\n<p class=\"subtitle\">"
      << html_escape(in.scene.description) << ". avalanche-hazard "
      << keyed(summary, "software_version") << ", configuration "
      << keyed(summary, "config_hash", "code") << ".</p>\n<ul class=\"note\">";
    for (const auto& note : in.scene.input_notes) s << "<li>" << html_escape(note) << "</li>";
    s << "</ul>";
    // An interrupted run's maps hold only what happened before the signal: say so before
    // anything else, so that nobody draws a zone from them (summary.json: complete).
    if (in.stats.end_reason == EndReason::interrupted)
        s << "<p class=\"incomplete\" style=\"border:3px solid #c00;padding:0.6em;"
             "font-weight:bold\">INCOMPLETE: the run was interrupted at t = "
          << html_escape(std::to_string(in.stats.simulated_time))
          << " s. The maps and numbers below cover only the flow up to then. Continue it with "
             "<code>avalanche-hazard run --resume</code> on this folder.</p>";
    // What the maps do not show by themselves (run_caveats.hpp), as prominent.
    if (!in.caveats.empty()) {
        s << "<div class=\"caveats\"><b>Caveats of this run: the maps may understate the hazard.</b><ul>";
        for (const auto& c : in.caveats) {
            // The log's "m3" as the rest of this report writes it.
            std::string text = html_escape(c.message);
            for (auto p = text.find(" m3 "); p != std::string::npos; p = text.find(" m3 ", p))
                text.replace(p + 2, 1, "³");
            s << "<li data-code=\"" << html_escape(c.code) << "\">" << text << "</li>";
        }
        s << "</ul></div>";
    }
    s << "</header>\n";
    return s.str();
}

std::string brief_section(const nlohmann::json& summary) {
    auto k = [&](const std::string& key) { return keyed(summary, key); };
    auto row = [&](const char* label, const std::string& key, const char* units) {
        return std::string("<tr><th>") + label + "</th>" + keyed(summary, key, "td") + "<td>" +
               units + "</td></tr>\n";
    };
    std::ostringstream s;
    s << "<section id=\"brief\"><h2>Results in brief</h2>\n<p class=\"brief\">A volume of "
      << k("volume.released_m3") << " m³ was released. The flow travelled "
      << k("runout.runout_length_m")
      << " m horizontally from the top of the release area to the farthest point it reached, "
         "and dropped "
      << k("runout.fall_height_m") << " m in height on the way: a travel angle of "
      << k("runout.travel_angle_deg") << "°. It reached an area of " << k("runout.affected_area_m2")
      << " m², with speeds up to " << k("runout.max_velocity_ms")
      << " m/s and impact pressures up to " << k("runout.max_pressure_kpa") << " kPa. At the end, "
      << k("runout.deposit_volume_m3") << " m³ lay in the deposit.</p>\n<table>\n"
      << row("runout length L (horizontal, top of the release to the farthest reached point)",
             "runout.runout_length_m", "m")
      << row("fall height H (top of the release minus the farthest point)", "runout.fall_height_m",
             "m")
      << row("travel angle atan(H / L)", "runout.travel_angle_deg", "deg")
      << row("runout efficiency L / H", "runout.runout_efficiency", "")
      << row("affected area (depth at least output.h_threshold at some time)",
             "runout.affected_area_m2", "m²")
      << row("deposit volume (thicker than output.h_threshold at the end)",
             "runout.deposit_volume_m3", "m³")
      << row("maximum flow depth (bed-normal)", "runout.max_depth_m", "m")
      << row("maximum speed", "runout.max_velocity_ms", "m/s")
      << row("maximum impact pressure", "runout.max_pressure_kpa", "kPa")
      << row("released volume", "volume.released_m3", "m³")
      << row("simulated time", "simulated_time_s", "s") << row("end of the run", "end_reason", "")
      << row("kinetic energy at the end, as a fraction of its maximum",
             "final_kinetic_energy_fraction", "")
      << "</table></section>\n";
    return s.str();
}

// A colour swatch of hazard class k in the palette of the maps.
std::string class_swatch(std::size_t k) {
    const gis::Rgba c = gis::hazard_class_palette().stops.at(k).color;
    if (c.a == 0) return "<span class=\"swatch none\"></span>";
    char buf[80];
    std::snprintf(buf, sizeof buf,
                  "<span class=\"swatch\" style=\"background:#%02x%02x%02x\"></span>", c.r, c.g,
                  c.b);
    return buf;
}

std::string hazard_section(const nlohmann::json& summary) {
    const std::string low = keyed(summary, "parameters.output.pressure_low_kpa");
    const std::string high = keyed(summary, "parameters.output.pressure_high_kpa");
    const std::string thr = keyed(summary, "parameters.output.h_threshold");
    std::ostringstream s;
    s << "<section id=\"hazard\"><h2>Hazard classes</h2>\n<p>Every place the flow reached "
         "(depth at least "
      << thr
      << " m at some time) gets a class from the <b>highest impact pressure</b> it felt there; "
         "the flow depth only decides whether a place counts as reached. The classes follow "
         "the intensity part of Alpine avalanche zoning (red, blue and yellow zones as in "
         "Switzerland; the limits are parameters of the run, "
         "<code>output.pressure_low_kpa</code> and <code>output.pressure_high_kpa</code>).</p>\n"
         "<table class=\"classes\"><tr><th>class</th><th>rule</th><th>what it means for land "
         "use</th></tr>\n"
      << "<tr><td>" << class_swatch(3) << "high (red)</td><td>pressure " << high
      << " kPa or more</td><td>Buildings can be destroyed; people are in danger inside "
         "buildings. In zoning practice: no new buildings for people.</td></tr>\n"
      << "<tr><td>" << class_swatch(2) << "medium (blue)</td><td>from " << low << " to " << high
      << " kPa</td><td>People are in danger outside buildings; buildings can be damaged. In "
         "zoning practice: building only with conditions (reinforced walls facing the slope, "
         "protected openings), evacuation plans.</td></tr>\n"
      << "<tr><td>" << class_swatch(1) << "low (yellow)</td><td>below " << low
      << " kPa</td><td>Reached by the flow with little pressure: the danger is low but not "
         "absent. In zoning practice: a hint zone; avoid sensitive uses such as schools or "
         "camping grounds.</td></tr>\n"
      << "<tr><td>" << class_swatch(0) << "not reached</td><td>depth below " << thr
      << " m throughout</td><td>Not reached in <i>this</i> scenario.</td></tr>\n</table>\n"
      << "<p class=\"note\">A hazard zone plan also weighs how often an event occurs (return "
         "period) and uses several scenarios; this map is one scenario with one set of "
         "friction angles. The Coulomb friction model has no speed-dependent drag, so speeds "
         "and pressures are upper estimates. Compare several friction angles "
         "(<code>avalanche-hazard batch</code>) before drawing a line.</p></section>\n";
    return s.str();
}

std::string maps_section(const std::string& dir, const ProductInputs& in) {
    const Grid& g = in.scene.grid;
    MapOverlay overlay;
    overlay.grid = g;
    if (!in.scene.crs_wkt.empty())
        overlay.crs_label = gis::GeoGrid{g, in.scene.crs_wkt}.crs_label();
    // The release as rasterized: the cells that held material at the start.
    overlay.release = in.release_cells;
    if (in.probes) overlay.points = in.probes->points();
    overlay.no_terrain_data = !in.scene.outside_data.empty();

    std::ostringstream s;
    s << "<section id=\"maps\"><h2>Maps</h2>\n<p>Each map is also a GeoTIFF in this folder "
         "(open it in QGIS: the <code>.qml</code> style beside it colours it the same way).</p>\n"
      << map_notes_html(overlay);
    for (MapFigure f : map_figures(in)) {
        f.png = detail::read_file_bytes((std::filesystem::path(dir) / (f.id + ".png")).string());
        s << map_figure_html(f, overlay) << "\n";
    }
    s << "</section>\n";
    return s.str();
}

std::string files_section(const nlohmann::json& summary) {
    std::ostringstream s;
    s << "<section id=\"files\"><h2>Files of this run</h2>\n<ul>";
    if (const nlohmann::json* products = detail::json_at(summary, "products"))
        for (const auto& f : *products) {
            const std::string name = html_escape(detail::json_text(f));
            s << "<li><a href=\"" << name << "\">" << name << "</a></li>";
        }
    s << "<li><a href=\"results.h5\">results.h5</a>: snapshots of depth and velocity</li>"
      << "<li><a href=\"summary.json\">summary.json</a>: every number of this report</li>"
      << "</ul></section>\n";
    return s.str();
}

}  // namespace

std::string write_report_html(const std::string& dir, const ProductInputs& in,
                              const nlohmann::json& summary) {
    const std::string body = header(in, summary) + brief_section(summary) +
                             hazard_section(summary) + maps_section(dir, in) +
                             detail::monitoring_section(in, summary) +
                             detail::run_section(summary) + detail::parameters_section(summary) +
                             detail::provenance_section(summary) + files_section(summary);
    write_file_atomically((std::filesystem::path(dir) / "report.html").string(),
                          detail::html_document("Avalanche hazard report", body));
    return "report.html";
}

}  // namespace avalanche
