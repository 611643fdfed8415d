#include "avalanche/io/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace avalanche {

namespace {

constexpr double kWidth = 640, kHeight = 420;
constexpr double kLeft = 70, kRight = 150, kTop = 40, kBottom = 55;  // margins (px)
// Colour-blind-safe palette (Okabe & Ito 2008).
constexpr const char* kColors[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                   "#E69F00", "#56B4E9", "#F0E442", "#000000"};

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else if (c == '"')
            out += "&quot;";
        else
            out += c;
    }
    return out;
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

// "Nice" tick spacing (1, 2 or 5 x 10^k) giving about five ticks over [lo, hi].
double tick_step(double lo, double hi) {
    const double raw = (hi - lo) / 5.0;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 5.0})
        if (raw <= m * mag) return m * mag;
    return 10.0 * mag;
}

struct Range {
    double lo = 0, hi = 1;
    void pad() {
        if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) {
            lo -= 1.0;  // one value: centre it in a unit-wide window
            hi += 1.0;
        }
    }
};

}  // namespace

std::string svg_line_plot(const LinePlot& plot) {
    Range rx{1e300, -1e300}, ry{1e300, -1e300};
    for (const auto& s : plot.series)
        for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k) {
            if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
            rx.lo = std::min(rx.lo, s.x[k]);
            rx.hi = std::max(rx.hi, s.x[k]);
            ry.lo = std::min(ry.lo, s.y[k]);
            ry.hi = std::max(ry.hi, s.y[k]);
        }
    if (rx.lo > rx.hi) rx = {0, 1};
    if (ry.lo > ry.hi) ry = {0, 1};
    rx.pad();
    ry.pad();
    const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
    auto px = [&](double x) { return kLeft + (x - rx.lo) / (rx.hi - rx.lo) * pw; };
    auto py = [&](double y) { return kTop + ph - (y - ry.lo) / (ry.hi - ry.lo) * ph; };

    std::ostringstream o;
    o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << kWidth / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">"
      << escape(plot.title) << "</text>\n";
    o << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"black\"/>\n";
    for (int axis = 0; axis < 2; ++axis) {
        const Range& r = axis == 0 ? rx : ry;
        const double step = tick_step(r.lo, r.hi);
        for (double t = std::ceil(r.lo / step) * step; t <= r.hi + 1e-9 * step; t += step) {
            const double v = std::abs(t) < 1e-9 * step ? 0.0 : t;
            if (axis == 0)
                o << "<line x1=\"" << px(v) << "\" y1=\"" << kTop + ph << "\" x2=\"" << px(v)
                  << "\" y2=\"" << kTop + ph + 5 << "\" stroke=\"black\"/><text x=\"" << px(v)
                  << "\" y=\"" << kTop + ph + 18 << "\" text-anchor=\"middle\">" << num(v)
                  << "</text>\n";
            else
                o << "<line x1=\"" << kLeft - 5 << "\" y1=\"" << py(v) << "\" x2=\"" << kLeft
                  << "\" y2=\"" << py(v) << "\" stroke=\"black\"/><text x=\"" << kLeft - 8
                  << "\" y=\"" << py(v) + 4 << "\" text-anchor=\"end\">" << num(v) << "</text>\n";
        }
    }
    o << "<text x=\"" << kLeft + pw / 2 << "\" y=\"" << kHeight - 12 << "\" text-anchor=\"middle\">"
      << escape(plot.x_label) << "</text>\n"
      << "<text transform=\"translate(16," << kTop + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << escape(plot.y_label) << "</text>\n";

    int legend_row = 0;
    for (std::size_t s = 0; s < plot.series.size(); ++s) {
        const auto& series = plot.series[s];
        const char* color = kColors[s % (sizeof kColors / sizeof *kColors)];
        // Past the eight colours, the lines are dashed so that no two series look alike.
        const std::size_t n_colors = sizeof kColors / sizeof *kColors;
        const std::string dash = s >= n_colors ? "\" stroke-dasharray=\"6,3" : "";
        std::ostringstream points, markers;
        for (std::size_t k = 0; k < std::min(series.x.size(), series.y.size()); ++k) {
            if (!std::isfinite(series.x[k]) || !std::isfinite(series.y[k])) continue;
            points << px(series.x[k]) << "," << py(series.y[k]) << " ";
            markers << "<circle cx=\"" << px(series.x[k]) << "\" cy=\"" << py(series.y[k])
                    << "\" r=\"3\" fill=\"" << color << "\"/>";
        }
        o << "<polyline fill=\"none\" stroke=\"" << color << dash << "\" stroke-width=\"2\" points=\""
          << points.str() << "\"/>\n"
          << markers.str() << "\n";
        if (series.label.empty()) continue;
        const double ly = kTop + 10 + 18 * legend_row++;
        o << "<line x1=\"" << kWidth - kRight + 12 << "\" y1=\"" << ly << "\" x2=\""
          << kWidth - kRight + 32 << "\" y2=\"" << ly << "\" stroke=\"" << color << dash
          << "\" stroke-width=\"2\"/><text x=\"" << kWidth - kRight + 37 << "\" y=\"" << ly + 4
          << "\">" << escape(series.label) << "</text>\n";
    }
    o << "</svg>\n";
    return o.str();
}

}  // namespace avalanche
