// Part 2 of the validation study: the laboratory chute of Koch, Greve & Hutter (1994) as
// simulated by Wang & Li (2017) section 3, Fig. 6 (scenarios/koch1994): front and tail on
// the centre line at the six times of the figure, an x-t diagram and the deposit.
#include <ctime>
#include <cmath>
#include <iostream>
#include <sstream>

#include "avalanche/io/svg_plot.hpp"
#include "validation_study.hpp"
#include "validation_text.hpp"

namespace avalanche::validation {

namespace {

// The moments of Wang & Li's Fig. 6 (a)-(f).
const std::vector<double> kPaperTimes = {0.6, 0.84, 1.04, 1.23, 1.62, 2.46};
// The lowest contour of Fig. 6 is the particle diameter: "Depth contour is depicted by
// color, with bottom value as the particle diameter (0.005 m)".
constexpr double kParticleDiameter = 0.005;
constexpr double kSnapshotInterval = 0.01;  // s; every time of Fig. 6 is a multiple

const char* zone(double x, double t0, double t1) {
    return x < t0 ? "plane" : x <= t1 ? "transition" : "runout";
}

}  // namespace

std::string koch_section(const StudyOptions& o) {
    ChuteCase c =
        chute_case_from_scenario(o.source_dir + "/scenarios/koch1994/scenario.toml", o.koch_cell);
    c.front_threshold = kParticleDiameter;
    c.numerics.output_interval = kSnapshotInterval;
    for (int k = 0; k * kSnapshotInterval <= c.numerics.t_end + 1e-9; ++k)
        c.probe_times.push_back(k * kSnapshotInterval);
    std::cerr << "Koch et al. (1994) chute (cells of " << c.cell_size << " m) ... " << std::flush;
    const std::clock_t t0 = std::clock();  // CPU time: one thread, and the machine is shared
    const ChuteOutcome r = run_chute_case(c);
    const double wall = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
    std::cerr << fmt("%.1f s", wall) << "\n";
    const double x0 = *c.geometry.transition_start, x1 = *c.geometry.transition_end;

    // x-t diagram of front and tail.
    PlotSeries front{"front", {}, {}}, tail{"tail", {}, {}}, paper{"Fig. 6 times", {}, {}};
    for (const FrontTail& f : r.probes) {
        if (!f.found) continue;
        front.x.push_back(f.t);
        front.y.push_back(f.front);
        tail.x.push_back(f.t);
        tail.y.push_back(f.tail);
    }
    // Thin down to one point in five: the markers would hide the lines.
    auto thin = [](PlotSeries s) {
        PlotSeries t{s.label, {}, {}};
        for (std::size_t k = 0; k < s.x.size(); k += 5) {
            t.x.push_back(s.x[k]);
            t.y.push_back(s.y[k]);
        }
        return t;
    };
    PlotSeries t_start{"transition start", {0.0, c.numerics.t_end}, {x0, x0}};
    PlotSeries t_end{"transition end", {0.0, c.numerics.t_end}, {x1, x1}};
    std::ostringstream md;
    md << kKochIntro;
    md << "\nCell size " << c.cell_size << " m (" << fmt("%.0f", c.cap.radius / c.cell_size)
       << " cells across the cap radius), WAF, CFL " << c.numerics.cfl
       << "; front/tail threshold " << kParticleDiameter * 1000 << " mm; " << r.stats.steps
       << " steps, " << fmt("%.0f", wall) << " s of CPU time (one thread). The run ended by "
       << to_string(r.stats.end_reason) << " at t = " << fmt("%.2f", r.stats.simulated_time)
       << " s; outflow " << fmt("%.1e", r.stats.outflow_volume) << " m^3, relative volume error "
       << fmt("%.1e", r.stats.relative_mass_error()) << ".\n\n";
    md << "| t (s) | Fig. 6 | tail x (m) | front x (m) | front zone | length (m) | tail - cap "
          "rear (m) | front - cap front (m) | max depth on centre line (mm) |\n"
          "|---|---|---|---|---|---|---|---|---|\n";
    const double cap_rear = c.cap.center[0] - c.cap.radius, cap_front = c.cap.center[0] + c.cap.radius;
    const char* panels = "abcdef";
    for (std::size_t k = 0; k < kPaperTimes.size(); ++k) {
        const FrontTail* f = nullptr;
        for (const FrontTail& p : r.probes)
            if (std::abs(p.t - kPaperTimes[k]) < 0.5 * kSnapshotInterval) f = &p;
        md << "| " << kPaperTimes[k] << " | (" << panels[k] << ") | ";
        if (!f || !f->found) {
            md << "- | - | - | - | - | - | - |\n";
            continue;
        }
        md << fmt("%.3f", f->tail) << " | " << fmt("%.3f", f->front) << " | "
           << zone(f->front, x0, x1) << " | " << fmt("%.3f", f->front - f->tail) << " | "
           << fmt("%.3f", f->tail - cap_rear) << " | " << fmt("%.3f", f->front - cap_front) << " | "
           << fmt("%.1f", 1000 * f->max_depth) << " |\n";
    }
    const FrontTail& d = r.deposit_extent;
    md << "| end (" << fmt("%.2f", r.stats.simulated_time) << ") | deposit | "
       << (d.found ? fmt("%.3f", d.tail) : "-") << " | " << (d.found ? fmt("%.3f", d.front) : "-")
       << " | " << (d.found ? zone(d.front, x0, x1) : "-") << " | "
       << (d.found ? fmt("%.3f", d.front - d.tail) : "-") << " | | | "
       << fmt("%.1f", 1000 * d.max_depth) << " |\n";
    md << "\nDeposit: width " << fmt("%.3f", r.deposit_width) << " m, deepest "
       << fmt("%.1f", 1000 * r.deposit_max_depth) << " mm; the tail "
       << (!d.found ? "is not defined (no deposit)"
           : std::string("is ") + (d.tail < x0 ? "on the plane" : d.tail <= x1 ? "in the transition" : "on the runout"))
       << ".\n\n![Koch x-t](figures/validation/koch_front_tail.svg)\n";
    write_svg(o, "koch_front_tail.svg",
              svg_line_plot({"Koch et al. (1994) No. 1: front and tail on the centre line",
                             "t (s)", "x along the bed (m)",
                             {thin(front), thin(tail), t_start, t_end}}));
    md << kKochDiscussion;
    return md.str();
}

}  // namespace avalanche::validation
