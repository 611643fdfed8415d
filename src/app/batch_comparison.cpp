// comparison.csv, comparison.md and the SVG trend plots of a batch, from each
// scenario's summary.json (numbers copied as JSON spells them, so they equal the summary).
#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/csv_text.hpp"
#include "avalanche/io/svg_plot.hpp"
#include "batch_outputs.hpp"

namespace avalanche::detail {

namespace {

// comparison.csv column -> key in summary.json's "runout" section.
const std::pair<const char*, const char*> kRunoutColumns[] = {
    {"runout_m", "runout_length_m"},
    {"travel_angle_deg", "travel_angle_deg"},
    {"runout_efficiency", "runout_efficiency"},
    {"affected_area_m2", "affected_area_m2"},
    {"max_depth_m", "max_depth_m"},
    {"max_velocity_ms", "max_velocity_ms"},
    {"deposit_volume_m3", "deposit_volume_m3"},
};

// A JSON value as a cell: numbers exactly as in summary.json, null as empty.
std::string cell(const nlohmann::json& v) {
    if (v.is_null()) return "";
    if (v.is_string()) return v.get<std::string>();
    return v.dump();
}

std::string value_of(const BatchResult& r, const SweepParameter* p) {
    for (const auto& [q, v] : r.batch_case->values)
        if (q == p) return v;
    return "";
}

// Monitoring point names over all scenarios, in first-seen order.
std::vector<std::string> point_names(const std::vector<const BatchResult*>& rows) {
    std::vector<std::string> names;
    for (const auto* r : rows) {
        if (!r->summary || !r->summary->contains("monitoring_points")) continue;
        for (const auto& p : (*r->summary)["monitoring_points"]) {
            const auto name = p.at("name").get<std::string>();
            if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        }
    }
    return names;
}

nlohmann::json arrival_at(const nlohmann::json& summary, const std::string& point) {
    if (!summary.contains("monitoring_points")) return nullptr;
    for (const auto& p : summary["monitoring_points"])
        if (p.at("name") == point) return p.at("arrival_time_s");
    return nullptr;
}

double runout_of(const BatchResult& r) {
    return r.summary->at("runout").at("runout_length_m").get<double>();
}

// One series per combination of the other swept parameters, sorted along `p`.
LinePlot trend_plot(const std::vector<const BatchResult*>& rows, const SweepParameter* p,
                    const std::vector<const SweepParameter*>& params, const char* metric,
                    const char* metric_label) {
    std::map<std::string, std::vector<std::pair<double, double>>> groups;
    for (const auto* r : rows) {
        if (!r->summary) continue;
        std::string label;
        for (const auto* q : params)
            if (q != p)
                label += (label.empty() ? "" : ", ") + std::string(q->name) + "=" + value_of(*r, q);
        groups[label].emplace_back(std::stod(value_of(*r, p)),
                                   r->summary->at("runout").at(metric).get<double>());
    }
    LinePlot plot{std::string(metric_label) + " vs " + p->column, p->column, metric_label, {}};
    for (auto& [label, points] : groups) {
        std::sort(points.begin(), points.end());
        PlotSeries s{label, {}, {}};
        for (const auto& [x, y] : points) {
            s.x.push_back(x);
            s.y.push_back(y);
        }
        plot.series.push_back(std::move(s));
    }
    return plot;
}

// The fit columns (jaccard, runout_error_m, fit_score, fit_rank), each with a leading
// comma; numbers in JSON's shortest round-trip spelling, as the other columns.
std::string fit_cells(const std::optional<ScenarioFit>& f) {
    if (!f) return ",,,,";
    std::ostringstream s;
    s << ',' << nlohmann::json(f->jaccard).dump() << ',' << nlohmann::json(f->runout_error_m).dump()
      << ',' << nlohmann::json(f->score).dump() << ',' << f->rank;
    return s.str();
}

// comparison.md's ranking against the observed deposit, best first.
std::string ranking_section(const std::vector<const BatchResult*>& rows,
                            const std::string& observed) {
    std::vector<const BatchResult*> ranked;
    for (const auto* r : rows)
        if (r->fit) ranked.push_back(r);
    std::sort(ranked.begin(), ranked.end(), [](const BatchResult* a, const BatchResult* b) {
        return a->fit->rank < b->fit->rank;
    });
    std::ostringstream md;
    md << "\n## Fit to the observed deposit\n\nObserved: `" << observed << "`. ";
    if (ranked.empty()) {
        md << "No scenario completed, so none is ranked.\n";
        return md.str();
    }
    // Ids can be long (many swept parameters): only the numbers go through snprintf.
    char buf[96];
    const ScenarioFit& best = *ranked.front()->fit;
    std::snprintf(buf, sizeof buf, "(Jaccard %.3f, runout error %+.1f m)", best.jaccard,
                  best.runout_error_m);
    md << "Best fit: **" << ranked.front()->batch_case->id << "** " << buf
       << ". Score = (1 - Jaccard) + |runout error| / observed runout; lower is better "
          "(docs/batch.md, `calibration.json`).\n\n| rank | id | Jaccard | runout error (m) | "
          "score |\n|---|---|---|---|---|\n";
    for (const auto* r : ranked) {
        std::snprintf(buf, sizeof buf, " | %.3f | %+.1f | %.3f |\n", r->fit->jaccard,
                      r->fit->runout_error_m, r->fit->score);
        md << "| " << r->fit->rank << " | " << r->batch_case->id << buf;
    }
    return md.str();
}

// The codes of a scenario's caveats (run_caveats.hpp), ';'-separated; empty without any.
std::string caveat_codes(const nlohmann::json& summary) {
    std::string codes;
    if (!summary.contains("caveats")) return codes;
    for (const auto& c : summary.at("caveats")) {
        if (!codes.empty()) codes += ';';
        codes += c.at("code").get<std::string>();
    }
    return codes;
}

}  // namespace

const char* outcome_label(ScenarioOutcome outcome) {
    switch (outcome) {
        case ScenarioOutcome::complete:
            return "complete";
        case ScenarioOutcome::failed:
            return "failed";
        case ScenarioOutcome::interrupted:
            return "interrupted";
        case ScenarioOutcome::not_run:
            return "not run";
    }
    return "failed";
}

std::vector<const SweepParameter*> swept_parameters(const std::vector<BatchResult>& rows) {
    std::vector<const SweepParameter*> out;
    if (!rows.empty())
        for (const auto& [p, v] : rows.front().batch_case->values) out.push_back(p);
    return out;
}

std::vector<std::string> write_comparison(const std::string& dir,
                                          const std::vector<BatchResult>& results,
                                          const std::string& base_scenario,
                                          const std::string& observed) {
    const std::filesystem::path d(dir);
    std::vector<const BatchResult*> rows;
    for (const auto& r : results) rows.push_back(&r);
    std::sort(rows.begin(), rows.end(), [](const BatchResult* a, const BatchResult* b) {
        return a->batch_case->id < b->batch_case->id;
    });
    const auto params = swept_parameters(results);
    const auto points = point_names(rows);

    std::ostringstream csv;
    csv << "id";
    for (const auto* p : params) csv << "," << p->column;
    for (const auto& [column, key] : kRunoutColumns) csv << "," << column;
    csv << ",end_reason,caveats";
    for (const auto& name : points) csv << "," << csv_field("arrival_s_" + name);
    const bool calibrated = !observed.empty();
    if (calibrated) csv << ",jaccard,runout_error_m,fit_score,fit_rank";
    csv << ",wall_s\n";
    for (const auto* r : rows) {
        csv << r->batch_case->id;
        for (const auto* p : params) csv << "," << csv_field(value_of(*r, p));
        if (r->summary) {
            const auto& runout = r->summary->at("runout");
            for (const auto& [column, key] : kRunoutColumns) csv << "," << cell(runout.at(key));
            csv << "," << cell(r->summary->at("end_reason")) << "," << caveat_codes(*r->summary);
            for (const auto& name : points) csv << "," << cell(arrival_at(*r->summary, name));
            if (calibrated) csv << fit_cells(r->fit);
            csv << "," << cell(r->summary->at("wall_s")) << "\n";
        } else {
            for (std::size_t k = 0; k < std::size(kRunoutColumns); ++k) csv << ",";
            csv << "," << outcome_label(r->outcome) << "," << std::string(points.size(), ',');
            if (calibrated) csv << ",,,,";
            csv << ",\n";
        }
    }
    write_file_atomically((d / "comparison.csv").string(), csv.str());
    std::vector<std::string> written{"comparison.csv"};

    // Plots: each numeric parameter with at least two values.
    std::vector<std::string> plots;
    for (const auto* p : params) {
        std::set<std::string> values;
        for (const auto* r : rows) values.insert(value_of(*r, p));
        if (!p->numeric || values.size() < 2) continue;
        for (const auto& [metric, label, file] :
             {std::tuple{"runout_length_m", "runout (m)", "runout"},
              std::tuple{"max_velocity_ms", "max velocity (m/s)", "max_velocity"}}) {
            const std::string name = std::string(file) + "_vs_" + p->column + ".svg";
            write_file_atomically((d / name).string(),
                                  svg_line_plot(trend_plot(rows, p, params, metric, label)));
            plots.push_back(name);
        }
    }
    written.insert(written.end(), plots.begin(), plots.end());

    // comparison.md: the table a planner reads first.
    std::ostringstream md;
    md << "# Batch comparison\n\nBase scenario: `" << base_scenario << "`; " << rows.size()
       << " scenarios. Every scenario's products are in its folder `<id>/`.\n\n| id |";
    for (const auto* p : params) md << " " << p->column << " |";
    md << " runout (m) | travel angle (deg) | max velocity (m/s) | affected area (m²) | end "
          "|\n|---|";
    for (std::size_t k = 0; k < params.size() + 5; ++k) md << "---|";
    md << "\n";
    const BatchResult *longest = nullptr, *shortest = nullptr;
    for (const auto* r : rows) {
        // Only reports this batch's scenarios wrote: one never started may keep an earlier
        // batch's folder, and one that failed early has none.
        const std::string& id = r->batch_case->id;
        if (r->outcome != ScenarioOutcome::not_run && std::filesystem::exists(d / id / "report.md"))
            md << "| [" << id << "](" << id << "/report.md) |";
        else
            md << "| " << id << " |";
        for (const auto* p : params) md << " " << value_of(*r, p) << " |";
        if (!r->summary) {
            md << " | | | | " << outcome_label(r->outcome);
            if (r->outcome == ScenarioOutcome::failed) md << ": " << r->failure;
            md << " |\n";
            continue;
        }
        const auto& ro = r->summary->at("runout");
        char buf[160];
        std::snprintf(
            buf, sizeof buf, " %.1f | %.1f | %.1f | %.0f | %s",
            ro.at("runout_length_m").get<double>(), ro.at("travel_angle_deg").get<double>(),
            ro.at("max_velocity_ms").get<double>(), ro.at("affected_area_m2").get<double>(),
            r->summary->at("end_reason").get<std::string>().c_str());
        md << buf;
        if (const std::string codes = caveat_codes(*r->summary); !codes.empty())
            md << " (" << codes << ")";
        md << " |\n";
        if (!longest || runout_of(*r) > runout_of(*longest)) longest = r;
        if (!shortest || runout_of(*r) < runout_of(*shortest)) shortest = r;
    }
    if (longest) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "\nLongest runout: **%s** (%.1f m). Shortest runout: **%s** (%.1f m).\n",
                      longest->batch_case->id.c_str(), runout_of(*longest),
                      shortest->batch_case->id.c_str(), runout_of(*shortest));
        md << buf;
    }
    // The maps across the scenarios are written only from complete ones (write_envelopes):
    // without any, DIR may hold only an earlier batch's.
    if (longest)
        md << "\nAcross the scenarios: `impact_frequency.tif` (fraction of scenarios reaching "
              "each cell), `envelope_max_depth.tif`, `envelope_max_velocity.tif`, "
              "`envelope_max_pressure.tif`, `envelope_min_arrival_time.tif`; all values in "
              "`comparison.csv`.\n";
    if (calibrated) md << ranking_section(rows, observed);
    if (!plots.empty()) {
        md << "\n";
        for (const auto& p : plots) md << "![" << p << "](" << p << ")\n";
    }
    write_file_atomically((d / "comparison.md").string(), md.str());
    written.push_back("comparison.md");
    return written;
}

}  // namespace avalanche::detail
