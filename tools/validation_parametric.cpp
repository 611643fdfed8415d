// Part 1 of the validation study: the parametric study of Wang & Li (2017) section 2.3
// (Figs. 2-5) on the shipped scenarios scenarios/paper_slope{30,45,60}, and the paper's
// qualitative findings checked one by one against our numbers.
#include <algorithm>
#include <ctime>
#include <functional>
#include <cmath>
#include <iostream>
#include <map>
#include <numbers>
#include <sstream>
#include <tuple>

#include "avalanche/io/svg_plot.hpp"
#include "avalanche/physics/earth_pressure.hpp"
#include "validation_study.hpp"
#include "validation_text.hpp"

namespace avalanche::validation {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
const std::vector<double> kDeltas = {10, 15, 20, 25, 30, 35};  // Figs. 2 and 5
const std::vector<double> kPhis = {20, 25, 30, 35};             // Fig. 3
const std::vector<double> kSlopes = {30, 45, 60};               // Fig. 5

struct CaseResult {
    double slope = 0, delta = 0, phi = 0;
    ChuteOutcome out;
    double wall = 0;
};

// One run per (slope, delta, phi); the 45 deg, phi 35 deg series is shared by Figs. 2 and 5.
class Runs {
public:
    explicit Runs(const StudyOptions& o) : o_(o) {}
    // cell_size 0: the study's (o.chute_cell, or the scenario's when that is 0).
    const CaseResult& get(double slope, double delta, double phi, double cell_size = 0.0) {
        const auto key = std::make_tuple(slope, delta, phi, cell_size);
        auto it = runs_.find(key);
        if (it != runs_.end()) return it->second;
        const std::string path =
            o_.source_dir + "/scenarios/paper_slope" + fmt("%.0f", slope) + "/scenario.toml";
        ChuteCase c = chute_case_from_scenario(path, cell_size > 0.0 ? cell_size : o_.chute_cell);
        if (cell_size <= 0.0) cell_ = c.cell_size;
        c.material.delta_deg = delta;
        c.material.phi_deg = phi;
        std::cerr << "  slope " << slope << ", delta " << delta << ", phi " << phi << ", cells "
                  << c.cell_size << " m ... "
                  << std::flush;
        const std::clock_t t0 = std::clock();  // CPU time: one thread, and the machine is shared
        CaseResult r{slope, delta, phi, run_chute_case(c), 0.0};
        r.wall = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
        std::cerr << fmt("%.1f s", r.wall) << "\n";
        total_wall_ += r.wall;
        return runs_.emplace(key, std::move(r)).first->second;
    }
    [[nodiscard]] double total_wall() const { return total_wall_; }
    [[nodiscard]] std::size_t count() const { return runs_.size(); }
    [[nodiscard]] double cell() const { return cell_; }

private:
    const StudyOptions& o_;
    std::map<std::tuple<double, double, double, double>, CaseResult> runs_;
    double total_wall_ = 0;
    double cell_ = 0;
};

// Centre-line deposit profiles, cropped to where any of them holds material.
LinePlot profile_plot(const std::vector<const CaseResult*>& cases, const std::string& title,
                      const std::function<std::string(const CaseResult&)>& label) {
    double lo = 1e300, hi = -1e300;
    for (const CaseResult* c : cases) {
        if (!c->out.deposit_extent.found) continue;
        lo = std::min(lo, c->out.deposit_extent.tail);
        hi = std::max(hi, c->out.deposit_extent.front);
    }
    lo -= 3.0;
    hi += 3.0;
    LinePlot p{title, "x along the bed (m); runout starts at x = 30 m",
               "final depth on the centre line (m, bed-normal)", {}};
    for (const CaseResult* c : cases) {
        PlotSeries s;
        s.label = label(*c);
        for (std::size_t i = 0; i < c->out.x.size(); ++i)
            if (c->out.x[i] >= lo && c->out.x[i] <= hi) {
                s.x.push_back(c->out.x[i]);
                s.y.push_back(c->out.deposit[i]);
            }
        p.series.push_back(std::move(s));
    }
    return p;
}

std::string delta_label(const CaseResult& c) { return "delta " + fmt("%.0f", c.delta); }
std::string phi_label(const CaseResult& c) { return "phi " + fmt("%.0f", c.phi); }

std::string case_row(const CaseResult& c) {
    const ChuteOutcome& o = c.out;
    std::ostringstream s;
    s << "| " << fmt("%.0f", c.slope) << " | " << fmt("%.0f", c.delta) << " | "
      << fmt("%.0f", c.phi) << " | " << fmt("%.1f", o.runout.runout_length_m) << " | "
      << fmt("%.2f", o.runout.fall_height_m) << " | " << fmt("%.2f", o.runout.runout_efficiency)
      << " | " << fmt("%.1f", o.runout.travel_angle_deg) << " | "
      << (o.deposit_extent.found ? fmt("%.1f", o.deposit_extent.tail) + " - " +
                                       fmt("%.1f", o.deposit_extent.front)
                                 : std::string("-"))
      << " | " << fmt("%.1f", o.deposit_width) << " | " << fmt("%.2f", o.deposit_max_depth)
      << " | " << to_string(o.stats.end_reason) << " at " << fmt("%.1f", o.stats.simulated_time)
      << " s | " << fmt("%.1e", o.stats.outflow_volume) << " | " << fmt("%.1f", c.wall) << " |\n";
    return s.str();
}

const char* kCaseHeader =
    "| slope (deg) | delta (deg) | phi (deg) | runout L (m) | fall height H (m) | RE = L/H | "
    "travel angle (deg) | deposit on centre line, tail - front x (m) | deposit width (m) | max "
    "deposit depth (m) | end | outflow (m^3) | CPU (s) |\n"
    "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";

std::string yes_no(bool b) { return b ? "**yes**" : "**no**"; }

// Verdict on a trend: strict, or monotone with ties (widths count whole cells), or not.
template <class F>
std::string trend(const std::vector<const CaseResult*>& v, F value, bool decreasing) {
    bool strict = true, weak = true;
    for (std::size_t k = 1; k < v.size(); ++k) {
        const double a = value(*v[k - 1]), b = value(*v[k]);
        strict = strict && (decreasing ? b < a : b > a);
        weak = weak && (decreasing ? b <= a : b >= a);
    }
    if (strict) return "**yes**";
    if (weak) return "**yes**, with ties (counted in whole cells)";
    return "**no**";
}

template <class F>
bool strictly(const std::vector<const CaseResult*>& v, F value, bool decreasing) {
    for (std::size_t k = 1; k < v.size(); ++k) {
        const double a = value(*v[k - 1]), b = value(*v[k]);
        if (decreasing ? !(b < a) : !(b > a)) return false;
    }
    return true;
}

std::string series_values(const std::vector<const CaseResult*>& v,
                          double (*value)(const CaseResult&), const char* f) {
    std::string s;
    for (std::size_t k = 0; k < v.size(); ++k) s += (k ? ", " : "") + fmt(f, value(*v[k]));
    return s;
}

double runout_of(const CaseResult& c) { return c.out.runout.runout_length_m; }
double re_of(const CaseResult& c) { return c.out.runout.runout_efficiency; }
double width_of(const CaseResult& c) { return c.out.deposit_width; }
double max_depth_of(const CaseResult& c) { return c.out.deposit_max_depth; }
double front_of(const CaseResult& c) { return c.out.deposit_extent.front; }
double length_of(const CaseResult& c) {
    return c.out.deposit_extent.front - c.out.deposit_extent.tail;
}

// Figure 4: the coefficients as the code computes them (earth_pressure.hpp).
void earth_pressure_figures(const StudyOptions& o, std::ostringstream& md) {
    auto series = [](const std::vector<double>& angles, bool vary_delta, double fixed) {
        std::vector<PlotSeries> s(4);
        s[0].label = "k_x active";
        s[1].label = "k_x passive";
        s[2].label = "k_y act | k_x act";
        s[3].label = "k_y pass | k_x pass";
        for (double a : angles) {
            const double phi = (vary_delta ? fixed : a) * kDeg, delta = (vary_delta ? a : fixed) * kDeg;
            const double ka = earth_pressure_kx(phi, delta, true);
            const double kp = earth_pressure_kx(phi, delta, false);
            const double v[4] = {ka, kp, earth_pressure_ky(ka, delta, true),
                                 earth_pressure_ky(kp, delta, false)};
            for (int k = 0; k < 4; ++k) {
                s[k].x.push_back(a);
                s[k].y.push_back(v[k]);
            }
        }
        return s;
    };
    std::vector<double> deltas, phis;
    for (double a = 0; a <= 35.0 + 1e-9; a += 1.0) deltas.push_back(a);
    for (double a = 20; a <= 50.0 + 1e-9; a += 1.0) phis.push_back(a);
    write_svg(o, "fig4a_earth_pressure_vs_delta.svg",
              svg_line_plot({"Fig. 4(a): earth pressure coefficients, phi = 35 deg",
                             "bed friction angle delta (deg)", "coefficient", series(deltas, true, 35)}));
    write_svg(o, "fig4b_earth_pressure_vs_phi.svg",
              svg_line_plot({"Fig. 4(b): earth pressure coefficients, delta = 20 deg",
                             "internal friction angle phi (deg)", "coefficient",
                             series(phis, false, 20)}));
    md << "\n![Fig. 4(a)](figures/validation/fig4a_earth_pressure_vs_delta.svg)\n"
       << "![Fig. 4(b)](figures/validation/fig4b_earth_pressure_vs_phi.svg)\n\n"
       << "| phi (deg) | delta (deg) | k_x active | k_x passive | k_y act given k_x act | k_y pass "
          "given k_x pass |\n|---|---|---|---|---|---|\n";
    for (auto [phi, delta] : std::vector<std::pair<double, double>>{
             {35, 0}, {35, 10}, {35, 20}, {35, 30}, {35, 35}, {20, 20}, {25, 20}, {30, 20}, {40, 20}, {50, 20}}) {
        const double ka = earth_pressure_kx(phi * kDeg, delta * kDeg, true);
        const double kp = earth_pressure_kx(phi * kDeg, delta * kDeg, false);
        md << "| " << phi << " | " << delta << " | " << fmt("%.3f", ka) << " | " << fmt("%.3f", kp)
           << " | " << fmt("%.3f", earth_pressure_ky(ka, delta * kDeg, true)) << " | "
           << fmt("%.3f", earth_pressure_ky(kp, delta * kDeg, false)) << " |\n";
    }
    // The paper's statements about Fig. 4, checked on a fine sweep of the same ranges.
    bool passive_above_one = true, active_decreasing = true, passive_increasing = true;
    double min_active = 1e300;
    double prev_a = 1e300, prev_p = -1e300;
    for (double phi : phis) {
        const double ka = earth_pressure_kx(phi * kDeg, 20 * kDeg, true);
        const double kp = earth_pressure_kx(phi * kDeg, 20 * kDeg, false);
        passive_above_one = passive_above_one && kp > 1.0;
        active_decreasing = active_decreasing && ka < prev_a;
        passive_increasing = passive_increasing && kp > prev_p;
        min_active = std::min(min_active, ka);
        prev_a = ka;
        prev_p = kp;
    }
    for (double d : deltas)
        passive_above_one =
            passive_above_one && earth_pressure_kx(35 * kDeg, d * kDeg, false) > 1.0;
    md << "\nThe paper's statements about Fig. 4, checked on the curves above (delta = 20 deg, phi "
          "= 20-50 deg; phi = 35 deg, delta = 0-35 deg):\n\n"
       << "| paper | ours |\n|---|---|\n"
       << "| \"The passive earth pressure coefficient increases with the internal friction "
          "angle\" | "
       << yes_no(passive_increasing) << " |\n"
       << "| \"... and is always larger than 1.0\" | " << yes_no(passive_above_one) << " |\n"
       << "| \"while the active earth pressure coefficient decreases with internal friction "
          "value\" | "
       << yes_no(active_decreasing) << " |\n"
       << "| \"and can be as small as about 0.5\" | smallest k_x active at delta = 20 deg: "
       << fmt("%.3f", min_active) << " (phi = 50 deg); " << fmt("%.3f", earth_pressure_kx(35 * kDeg, 20 * kDeg, true))
       << " at the reference phi = 35 deg |\n";
}

}  // namespace

std::string parametric_section(const StudyOptions& o) {
    std::ostringstream md;
    Runs runs(o);
    std::cerr << "parametric study\n";
    std::vector<const CaseResult*> by_delta, by_phi;
    for (double d : kDeltas) by_delta.push_back(&runs.get(45, d, 35));
    for (double p : kPhis) by_phi.push_back(&runs.get(45, 20, p));
    std::map<double, std::vector<const CaseResult*>> by_slope;
    for (double s : kSlopes)
        for (double d : kDeltas) by_slope[s].push_back(&runs.get(s, d, 35));

    md << kParametricIntro;
    md << "\nCell size " << runs.cell() << " m (" << fmt("%.0f", 2.5 / runs.cell())
       << " cells across the cap radius); " << runs.count() << " runs took "
       << fmt("%.0f", runs.total_wall()) << " s of CPU time (one thread).\n";

    // Fig. 2
    write_svg(o, "fig2_deposit_vs_delta.svg",
              svg_line_plot(profile_plot(by_delta, "Fig. 2: deposit on the centre line, phi = 35 deg",
                                         delta_label)));
    md << "\n### Fig. 2: bed friction delta = 10-35 deg at phi = 35 deg (45 deg slope)\n\n"
       << "![Fig. 2](figures/validation/fig2_deposit_vs_delta.svg)\n\n"
       << kCaseHeader;
    for (const CaseResult* c : by_delta) md << case_row(*c);

    // Fig. 3
    write_svg(o, "fig3_deposit_vs_phi.svg",
              svg_line_plot(profile_plot(by_phi, "Fig. 3: deposit on the centre line, delta = 20 deg",
                                         phi_label)));
    md << "\n### Fig. 3: internal friction phi = 20-35 deg at delta = 20 deg (45 deg slope)\n\n"
       << "![Fig. 3](figures/validation/fig3_deposit_vs_phi.svg)\n\n"
       << kCaseHeader;
    for (const CaseResult* c : by_phi) md << case_row(*c);

    // Fig. 4
    md << "\n### Fig. 4: earth pressure coefficients\n\n" << kEarthPressureText;
    earth_pressure_figures(o, md);

    // Fig. 5
    LinePlot re{"Fig. 5: runout efficiency, phi = 35 deg", "bed friction angle delta (deg)",
                "runout efficiency RE = L / H", {}};
    for (const auto& [slope, v] : by_slope) {
        PlotSeries s;
        s.label = fmt("%.0f", slope) + " deg slope";
        for (const CaseResult* c : v) {
            s.x.push_back(c->delta);
            s.y.push_back(c->out.runout.runout_efficiency);
        }
        re.series.push_back(std::move(s));
    }
    // The rigid block's ratio 1 / tan(delta) for reference (no spreading, no curvature).
    PlotSeries block;
    block.label = "1 / tan delta";
    for (double d : kDeltas) {
        block.x.push_back(d);
        block.y.push_back(1.0 / std::tan(d * kDeg));
    }
    re.series.push_back(block);
    write_svg(o, "fig5_runout_efficiency.svg", svg_line_plot(re));
    md << "\n### Fig. 5: runout efficiency against bed friction, slopes of 30, 45 and 60 deg\n\n"
       << "![Fig. 5](figures/validation/fig5_runout_efficiency.svg)\n\n"
       << kCaseHeader;
    for (double s : {30.0, 60.0})
        for (const CaseResult* c : by_slope[s]) md << case_row(*c);
    md << "\n(The 45 deg series is the table of Fig. 2.)\n";

    // The paper's findings against ours.
    const bool runout_dec = strictly(by_delta, runout_of, true);
    const bool front_dec = strictly(by_delta, front_of, true);
    double phi_lo = 1e300, phi_hi = -1e300;
    for (const CaseResult* c : by_phi) {
        phi_lo = std::min(phi_lo, runout_of(*c));
        phi_hi = std::max(phi_hi, runout_of(*c));
    }
    const double delta_span = runout_of(*by_delta.front()) - runout_of(*by_delta.back());
    bool re_monotone = true;
    std::string re_text;
    for (const auto& [slope, v] : by_slope) {
        const bool m = strictly(v, re_of, true);
        re_monotone = re_monotone && m;
        re_text += fmt("%.0f", slope) + " deg: " + series_values(v, re_of, "%.2f") +
                   (m ? " (strictly decreasing)" : " (**not** strictly decreasing)") + "; ";
    }
    double re_max_rough = 0, re_min_smooth = 1e300;
    for (const auto& [slope, v] : by_slope)
        for (const CaseResult* c : v) {
            if (c->delta > 15) re_max_rough = std::max(re_max_rough, re_of(*c));
            if (c->delta <= 10) re_min_smooth = std::min(re_min_smooth, re_of(*c));
        }

    md << "\n### The paper's findings and ours\n\n"
       << "| Wang & Li (2017) | ours (numbers above) | agree? |\n|---|---|---|\n"
       << "| \"There is clearly evident growth of runout distance with the reduction in bed "
          "friction angle\" (Fig. 2) | runout L for delta = 10..35: "
       << series_values(by_delta, runout_of, "%.1f") << " m; centre-line deposit front: "
       << series_values(by_delta, front_of, "%.1f") << " m | " << yes_no(runout_dec && front_dec)
       << " |\n"
       << "| \"the spread of landslides with a smaller bed friction angle extend wider, with a "
          "lower final maximum height\" (Fig. 2) | deposit width: "
       << series_values(by_delta, width_of, "%.1f") << " m; max deposit depth: "
       << series_values(by_delta, max_depth_of, "%.2f") << " m | wider " << trend(by_delta, width_of, true)
       << "; lower " << trend(by_delta, max_depth_of, false) << " |\n"
       << "| \"Averaged runout distances with the same bed friction angle but different internal "
          "friction angles are found to be almost the same\" (Fig. 3) | runout L for phi = 20..35: "
       << series_values(by_phi, runout_of, "%.1f") << " m: a spread of "
       << fmt("%.1f", phi_hi - phi_lo) << " m against " << fmt("%.1f", delta_span)
       << " m over delta = 10..35 | " << yes_no(phi_hi - phi_lo < 0.2 * delta_span) << " |\n"
       << "| \"however, the deposit varies greatly. Larger internal friction causes a wider "
          "spread with a lower maximum height in the streamwise direction\" (Fig. 3) | centre-line "
          "deposit length (front - tail): "
       << series_values(by_phi, length_of, "%.1f") << " m; max deposit depth: "
       << series_values(by_phi, max_depth_of, "%.2f") << " m; width: "
       << series_values(by_phi, width_of, "%.1f") << " m | longer "
       << trend(by_phi, length_of, false) << "; lower " << trend(by_phi, max_depth_of, true)
       << "; wider across the flow " << trend(by_phi, width_of, false) << " |\n"
       << "| \"We find that RE increases with the reduction of bed friction\" (Fig. 5) | " << re_text
       << " | " << yes_no(re_monotone) << " |\n"
       << "| \"For rough bed friction larger than 15 deg, RE never exceeds 2-3 ... For smooth bed "
          "friction cases, RE can be greater than 3\" (Fig. 5) | largest RE with delta > 15 deg: "
       << fmt("%.2f", re_max_rough) << "; smallest RE at delta = 10 deg: "
       << fmt("%.2f", re_min_smooth) << " | "
       << (re_min_smooth <= 3.0 ? std::string("**no**")
           : re_max_rough <= 3.0 ? std::string("**yes**")
           : re_max_rough <= 3.5
               ? "**roughly**: at most " + fmt("%.2f", re_max_rough) +
                     ", at the top of the paper's \"2-3\" band (read off its Fig. 5)"
               : std::string("**no**"))
       << " |\n";
    md << kParametricDiscussion;

    // How the 45 deg series moves with the cell size (coarser grids than the study's).
    std::vector<double> cells = {1.0, 0.5, 0.25, runs.cell()};
    std::sort(cells.begin(), cells.end(), std::greater<>());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    md << "\n**Cell size.** The 45 deg, phi = 35 deg series on three grids (runout L in m; "
          "in brackets the centre-line deposit front x in m); the study's grid is "
       << runs.cell() << " m:\n\n| delta (deg) |";
    for (double h : cells) md << " " << h << " m |";
    md << "\n|---|";
    for (std::size_t k = 0; k < cells.size(); ++k) md << "---|";
    md << "\n";
    for (double d : kDeltas) {
        md << "| " << d << " |";
        for (double h : cells) {
            const CaseResult& c = runs.get(45, d, 35, h == runs.cell() ? 0.0 : h);
            md << " " << fmt("%.1f", runout_of(c)) << " (" << fmt("%.1f", front_of(c)) << ") |";
        }
        md << "\n";
    }
    bool ordered = true;
    for (double h : cells) {
        std::vector<const CaseResult*> v;
        for (double d : kDeltas) v.push_back(&runs.get(45, d, 35, h == runs.cell() ? 0.0 : h));
        ordered = ordered && strictly(v, runout_of, true) && strictly(v, front_of, true);
    }
    md << "\nRunout and deposit front fall strictly with delta on every grid: "
       << yes_no(ordered) << ". The fast test (`PaperParametric.*`) asserts the orderings on "
       << "the 1 m grid.\n";
    return md.str();
}

}  // namespace avalanche::validation
