// DIR/report.html of a batch: the comparison table, the trend plots, the impact frequency
// map and the calibration ranking, read back from the files the batch wrote (so that this
// report does not depend on the batch's internal structures, and resumed batches get the
// same report as fresh ones). Only the files this batch wrote are read: DIR may still hold
// plots, a calibration or a frequency map of an earlier batch with other sweeps.
#include <algorithm>
#include <filesystem>
#include <sstream>

#include "avalanche/app/report_html.hpp"
#include "avalanche/app/report_html_map.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/gis/quicklook.hpp"
#include "avalanche/gis/raster_reader.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/html_text.hpp"
#include "report_html_parts.hpp"

namespace avalanche {

namespace {

namespace fs = std::filesystem;
using Table = std::vector<std::vector<std::string>>;

// RFC 4180 CSV: quoted fields may hold commas, doubled quotes and newlines.
Table parse_csv(const std::string& text) {
    Table rows(1);
    std::string field;
    bool quoted = false, any = false;
    for (std::size_t k = 0; k < text.size(); ++k) {
        const char c = text[k];
        if (quoted) {
            if (c == '"' && k + 1 < text.size() && text[k + 1] == '"')
                field += '"', ++k;
            else if (c == '"')
                quoted = false;
            else
                field += c;
        } else if (c == '"') {
            quoted = any = true;
        } else if (c == ',') {
            rows.back().push_back(field), field.clear(), any = true;
        } else if (c == '\n' || c == '\r') {
            if (c == '\r' && k + 1 < text.size() && text[k + 1] == '\n') ++k;
            if (any || !field.empty()) rows.back().push_back(field);
            field.clear(), any = false;
            if (!rows.back().empty()) rows.emplace_back();
        } else {
            field += c, any = true;
        }
    }
    if (any || !field.empty()) rows.back().push_back(field);
    if (rows.back().empty()) rows.pop_back();
    return rows;
}

bool is_number(const std::string& s, double& value) {
    if (s.empty()) return false;
    std::size_t used = 0;
    try {
        value = std::stod(s, &used);
    } catch (const std::exception&) {
        return false;
    }
    return used == s.size();
}

std::string comparison_section(const fs::path& dir, const Table& csv) {
    std::ostringstream s;
    s << "<section id=\"comparison\"><h2>Comparison of the scenarios</h2>\n";
    if (csv.size() < 2)
        return s.str() + "<p class=\"missing\">comparison.csv is empty.</p></section>\n";
    const auto& header = csv.front();
    const auto runout = std::find(header.begin(), header.end(), "runout_m") - header.begin();
    const auto end_reason = std::find(header.begin(), header.end(), "end_reason") - header.begin();
    s << "<p>One row per scenario (values rounded to 4 digits; exact values in "
         "<code>comparison.csv</code>). The id links to the scenario's own report.</p>\n"
         "<div class=\"wide\"><table class=\"comparison\"><tr>";
    // Long column names break after their underscores, not inside words.
    for (const auto& h : header) {
        std::string name = html_escape(h);
        for (auto p = name.find('_'); p != std::string::npos; p = name.find('_', p + 6))
            name.insert(p + 1, "<wbr>");
        s << "<th>" << name << "</th>";
    }
    s << "</tr>\n";
    std::string longest, shortest;
    double longest_m = -1e300, shortest_m = 1e300;
    for (std::size_t r = 1; r < csv.size(); ++r) {
        const auto& row = csv[r];
        const std::string id = row.empty() ? "" : row[0];
        // A scenario the batch never started may keep an earlier batch's folder and report.
        const bool not_run =
            static_cast<std::size_t>(end_reason) < row.size() && row[end_reason] == "not run";
        s << "<tr>";
        for (std::size_t c = 0; c < row.size(); ++c) {
            const std::string attrs = " data-id=\"" + html_escape(id) + "\" data-column=\"" +
                                      html_escape(c < header.size() ? header[c] : "") +
                                      "\" data-value=\"" + html_escape(row[c]) + "\"";
            double v = 0;
            if (c == 0 && !not_run && fs::exists(dir / id / "report.html"))
                s << "<td" << attrs << "><a href=\"" << html_escape(id) << "/report.html\">"
                  << html_escape(id) << "</a></td>";
            else if (c > 0 && is_number(row[c], v))
                s << "<td class=\"n\"" << attrs << ">" << format_number(v) << "</td>";
            else
                s << "<td" << attrs << ">" << html_escape(row[c]) << "</td>";
            if (static_cast<std::ptrdiff_t>(c) == runout && is_number(row[c], v)) {
                if (v > longest_m) longest_m = v, longest = id;
                if (v < shortest_m) shortest_m = v, shortest = id;
            }
        }
        s << "</tr>\n";
    }
    s << "</table></div>\n";
    // The scenarios whose maps may understate the hazard (run_caveats.hpp), named here
    // because they also shape the envelopes below.
    const auto caveats = std::find(header.begin(), header.end(), "caveats") - header.begin();
    std::vector<std::string> flagged;
    for (std::size_t r = 1; r < csv.size(); ++r)
        if (static_cast<std::size_t>(caveats) < csv[r].size() && !csv[r][caveats].empty())
            flagged.push_back(csv[r][0]);
    if (!flagged.empty()) {
        s << "<p class=\"caveats\"><b>" << flagged.size()
          << " of " << csv.size() - 1
          << " scenarios have caveats</b> (column <code>caveats</code>: <code>reached_edge</code>, the "
             "flow reached the end of the terrain; <code>not_stopped</code>, it was still moving at "
             "t_end): their maps, and the envelopes across the scenarios below, may understate the "
             "hazard. Each scenario's report says why:";
        for (const auto& id : flagged) s << " " << html_escape(id);
        s << ".</p>\n";
    }
    if (!longest.empty())
        s << "<p>Longest runout: <b>" << html_escape(longest) << "</b> ("
          << format_number(longest_m) << " m); shortest: <b>" << html_escape(shortest) << "</b> ("
          << format_number(shortest_m) << " m).</p>\n";
    s << "</section>\n";
    return s.str();
}

bool wrote(const std::vector<std::string>& files, const std::string& name) {
    return std::find(files.begin(), files.end(), name) != files.end();
}

std::string plots_section(const fs::path& dir, const std::vector<std::string>& files) {
    std::vector<fs::path> svgs;
    for (const auto& f : files)
        if (fs::path(f).extension() == ".svg" && f.find("_vs_") != std::string::npos)
            svgs.push_back(dir / f);
    std::sort(svgs.begin(), svgs.end());
    if (svgs.empty()) return "";
    std::ostringstream s;
    s << "<section id=\"plots\"><h2>Metrics against the parameters</h2>\n<p>How the runout and "
         "the maximum speed change with each swept parameter; one line per combination of "
         "the other parameters.</p>\n<div class=\"plots\">";
    for (const auto& p : svgs) s << inline_svg(detail::read_file_bytes(p.string())) << "\n";
    s << "</div></section>\n";
    return s.str();
}

// The impact frequency drawn over the hillshade of a scenario's computational DEM.
std::string frequency_section(const fs::path& dir, const Table& csv,
                              const std::vector<std::string>& files,
                              std::vector<std::string>& written) {
    const fs::path tif = dir / "impact_frequency.tif";
    if (!wrote(files, "impact_frequency.tif")) return "";
    const gis::RasterData freq = gis::read_geotiff(tif.string());
    std::vector<double> elevation(freq.values.size(), 0.0);
    for (std::size_t r = 1; r < csv.size(); ++r) {
        if (csv[r].empty()) continue;
        const fs::path dem = dir / csv[r][0] / "dem.tif";
        if (!fs::exists(dem)) continue;
        gis::RasterData z = gis::read_geotiff(dem.string());
        if (z.values.size() == elevation.size()) elevation = std::move(z.values);
        break;
    }
    gis::ColorRamp ramp;
    ramp.kind = gis::RampKind::discrete;
    ramp.stops = {{0.0, {254, 217, 118, 255}, "up to 25 %"},
                  {0.25, {254, 178, 76, 255}, "25 - 50 %"},
                  {0.5, {240, 59, 32, 255}, "50 - 75 %"},
                  {0.75, {189, 0, 38, 255}, "more than 75 %"}};
    const std::string png = (dir / "impact_frequency.png").string();
    gis::write_quicklook_png(png, freq.geo, freq.values, elevation, ramp,
                             freq.nodata.value_or(-9999.0));
    written.push_back("impact_frequency.png");
    MapFigure f{"impact_frequency",
                "Share of the scenarios that reached each place",
                "The share of the scenarios whose flow reached each place (depth at least "
                "output.h_threshold). Places reached in every scenario are the most certain; "
                "places reached by few scenarios depend on the uncertain parameters.",
                detail::read_file_bytes(png),
                ramp,
                "share of the scenarios"};
    MapOverlay overlay;
    overlay.grid = freq.geo.grid;
    if (!freq.geo.crs_wkt.empty()) overlay.crs_label = freq.geo.crs_label();
    return "<section id=\"frequency\"><h2>Impact frequency</h2>\n" + map_figure_html(f, overlay) +
           map_notes_html(overlay) +
           "<p class=\"note\">Worst cases over the scenarios: "
           "<code>envelope_max_depth.tif</code>, <code>envelope_max_velocity.tif</code>, "
           "<code>envelope_max_pressure.tif</code>, <code>envelope_min_arrival_time.tif</code> "
           "(open them in QGIS).</p></section>\n";
}

std::string cell_html(const nlohmann::json& v) {
    return v.is_object() ? "<code>" + html_escape(v.dump()) + "</code>"
                         : html_escape(detail::json_text(v));
}

// calibration.json, whatever its exact layout: scalars as a list, every array of objects
// as a table (the ranking), anything else as JSON text.
std::string calibration_section(const fs::path& dir, const std::vector<std::string>& files) {
    const fs::path path = dir / "calibration.json";
    if (!wrote(files, "calibration.json")) return "";
    std::ostringstream s;
    s << "<section id=\"calibration\"><h2>Calibration against the observation</h2>\n";
    nlohmann::json cal;
    try {
        cal = nlohmann::json::parse(detail::read_file_bytes(path.string()));
    } catch (const std::exception& e) {
        return s.str() +
               "<p class=\"missing\">calibration.json could not be read: " + html_escape(e.what()) +
               "</p></section>\n";
    }
    auto table = [&](const std::string& name, const nlohmann::json& rows) {
        std::vector<std::string> columns;
        for (const auto& r : rows)
            for (const auto& [key, v] : r.items())
                if (std::find(columns.begin(), columns.end(), key) == columns.end())
                    columns.push_back(key);
        s << "<h3>" << html_escape(name) << "</h3><table class=\"calibration\"><tr>";
        for (const auto& c : columns) s << "<th>" << html_escape(c) << "</th>";
        s << "</tr>\n";
        for (const auto& r : rows) {
            s << "<tr>";
            for (const auto& c : columns)
                s << "<td>" << (r.contains(c) ? cell_html(r[c]) : "") << "</td>";
            s << "</tr>\n";
        }
        s << "</table>\n";
    };
    auto is_table = [](const nlohmann::json& v) {
        return v.is_array() && !v.empty() &&
               std::all_of(v.begin(), v.end(), [](const auto& e) { return e.is_object(); });
    };
    if (is_table(cal)) {
        table("ranking", cal);
    } else if (cal.is_object()) {
        s << "<table>";
        for (const auto& [key, v] : cal.items())
            if (!is_table(v))
                s << "<tr><th>" << html_escape(key) << "</th><td>" << cell_html(v) << "</td></tr>";
        s << "</table>\n";
        for (const auto& [key, v] : cal.items())
            if (is_table(v)) table(key, v);
    } else {
        s << "<pre>" << html_escape(cal.dump(2)) << "</pre>";
    }
    s << "</section>\n";
    return s.str();
}

}  // namespace

std::vector<std::string> write_batch_report_html(const std::string& dir,
                                                 const std::string& base_scenario,
                                                 const std::vector<std::string>& batch_files) {
    const fs::path d(dir);
    const Table csv = parse_csv(detail::read_file_bytes((d / "comparison.csv").string()));
    std::vector<std::string> written;
    std::ostringstream body;
    body << "<header><h1>Avalanche hazard batch report</h1>\n<p class=\"subtitle\">"
         << (csv.empty() ? 0 : csv.size() - 1) << " scenarios from the base scenario <code>"
         << html_escape(base_scenario)
         << "</code>. Each scenario's maps and numbers are in its own folder and report "
            "(follow the ids).</p></header>\n"
         << comparison_section(d, csv) << calibration_section(d, batch_files)
         << plots_section(d, batch_files) << frequency_section(d, csv, batch_files, written);
    write_file_atomically((d / "report.html").string(),
                          detail::html_document("Avalanche hazard batch report", body.str()));
    written.push_back("report.html");
    return written;
}

}  // namespace avalanche
