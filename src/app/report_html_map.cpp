// A map of report.html: quick-look image, overlay (release, points, scale bar, north
// arrow) and legend.
#include "avalanche/app/report_html_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "avalanche/app/products.hpp"
#include "avalanche/io/html_text.hpp"

namespace avalanche {

namespace {

std::string px(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

std::string css_color(const gis::Rgba& c) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
    return buf;
}

std::string length_label(double metres) {
    char buf[32];
    if (metres >= 1000.0)
        std::snprintf(buf, sizeof buf, "%g km", metres / 1000.0);
    else
        std::snprintf(buf, sizeof buf, "%g m", metres);
    return buf;
}

// Scale bar in the lower left: two halves, black and white, labelled 0 and its length.
std::string scale_bar_svg(const MapOverlay& o, const MapDisplay& d) {
    const double length = scale_bar_length_m(o.grid.nx * o.grid.dx);
    const double bar = length * d.px_per_m;
    if (!(bar > 0) || bar > d.width - 20) return "";
    const double x = 14, y = d.height - 14;
    std::ostringstream s;
    s << "<g class=\"scale-bar\" data-length-m=\"" << length << "\" data-length-px=\"" << px(bar)
      << "\"><rect x=\"4\" y=\"" << px(y - 26) << "\" width=\"" << px(bar + 34)
      << "\" height=\"34\" rx=\"3\" fill=\"white\" fill-opacity=\"0.85\"/>"
      << "<rect x=\"" << px(x) << "\" y=\"" << px(y - 6) << "\" width=\"" << px(bar / 2)
      << "\" height=\"6\" fill=\"black\"/>"
      << "<rect x=\"" << px(x + bar / 2) << "\" y=\"" << px(y - 6) << "\" width=\"" << px(bar / 2)
      << "\" height=\"6\" fill=\"white\" stroke=\"black\" stroke-width=\"1\"/>"
      << "<text x=\"" << px(x) << "\" y=\"" << px(y - 11)
      << "\" text-anchor=\"middle\" font-size=\"11\">0</text>"
      << "<text x=\"" << px(x + bar) << "\" y=\"" << px(y - 11)
      << "\" text-anchor=\"middle\" font-size=\"11\">" << length_label(length) << "</text></g>";
    return s.str();
}

// North arrow in the upper right: the grid is north-up, so grid north is straight up.
std::string north_arrow_svg(const MapDisplay& d) {
    const double cx = d.width - 22;
    std::ostringstream s;
    s << "<g class=\"north-arrow\"><rect x=\"" << px(cx - 14) << "\" y=\"4\" width=\"28\" "
      << "height=\"48\" rx=\"3\" fill=\"white\" fill-opacity=\"0.85\"/>"
      << "<text x=\"" << px(cx) << "\" y=\"19\" text-anchor=\"middle\" font-size=\"13\" "
      << "font-weight=\"bold\">N</text><polygon points=\"" << px(cx) << ",22 " << px(cx + 8)
      << ",48 " << px(cx) << ",42 " << px(cx - 8) << ",48\" fill=\"black\"/></g>";
    return s.str();
}

std::string points_svg(const MapOverlay& o, const MapDisplay& d) {
    std::ostringstream s;
    for (const auto& p : o.points) {
        const double x = (p.x - o.grid.x0) * d.px_per_m, y = (o.grid.y_max() - p.y) * d.px_per_m;
        s << "<g class=\"point\"><circle cx=\"" << px(x) << "\" cy=\"" << px(y)
          << "\" r=\"5\" fill=\"white\" stroke=\"black\" stroke-width=\"2\"/><text x=\""
          << px(x + 8) << "\" y=\"" << px(y + 4)
          << "\" font-size=\"12\" paint-order=\"stroke\" stroke=\"white\" stroke-width=\"3\">"
          << html_escape(p.name) << "</text></g>";
    }
    return s.str();
}

}  // namespace

double scale_bar_length_m(double map_width_m) {
    if (!std::isfinite(map_width_m) || map_width_m <= 0) return 0.0;
    const double target = map_width_m / 5.0;
    const double decade = std::pow(10.0, std::floor(std::log10(target)));
    double best = decade, best_ratio = 1e300;
    for (double m : {1.0, 2.0, 5.0, 10.0}) {
        const double ratio = std::abs(std::log(m * decade / target));
        if (ratio < best_ratio) best = m * decade, best_ratio = ratio;
    }
    return best;
}

MapDisplay map_display(const Grid& g, double max_width, double max_height) {
    const double w = g.nx * g.dx, h = g.ny * g.dy;
    MapDisplay d;
    if (!(w > 0 && h > 0)) return d;
    d.px_per_m = std::min(max_width / w, max_height / h);
    d.width = w * d.px_per_m;
    d.height = h * d.px_per_m;
    return d;
}

std::string outline_path(const std::vector<std::uint8_t>& mask, const Grid& g, double px_per_m) {
    if (mask.size() != g.cells()) return "";
    auto in = [&](int i, int j) {
        return i >= 0 && i < g.nx && j >= 0 && j < g.ny &&
               mask[static_cast<std::size_t>(j) * g.nx + i] != 0;
    };
    const double cw = g.dx * px_per_m, ch = g.dy * px_per_m;
    // Display coordinates of the cell's west edge and north edge (row 0 at the top).
    auto left = [&](int i) { return i * cw; };
    auto top = [&](int j) { return (g.ny - 1 - j) * ch; };
    std::ostringstream s;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            if (!in(i, j)) continue;
            if (!in(i, j + 1)) s << "M" << px(left(i)) << " " << px(top(j)) << "h" << px(cw);
            if (!in(i, j - 1)) s << "M" << px(left(i)) << " " << px(top(j) + ch) << "h" << px(cw);
            if (!in(i - 1, j)) s << "M" << px(left(i)) << " " << px(top(j)) << "v" << px(ch);
            if (!in(i + 1, j)) s << "M" << px(left(i) + cw) << " " << px(top(j)) << "v" << px(ch);
        }
    return s.str();
}

std::string legend_html(const gis::ColorRamp& ramp, const std::string& title,
                        bool no_terrain_data) {
    std::ostringstream s;
    s << "<div class=\"legend\"><div class=\"legend-title\">" << html_escape(title) << "</div><ul>";
    if (ramp.kind == gis::RampKind::discrete && !ramp.draw_below_first && !ramp.stops.empty()) {
        std::ostringstream first;
        first << ramp.stops.front().value;
        const bool zero = ramp.stops.front().value == 0.0;
        s << "<li><span class=\"swatch none\"></span>" << (zero ? "" : "up to ") << first.str();
        if (!ramp.units.empty()) s << " " << html_escape(ramp.units);
        s << ": not coloured</li>";
    }
    for (const auto& stop : ramp.stops) {
        if (stop.color.a == 0)
            s << "<li><span class=\"swatch none\"></span>" << html_escape(stop.label)
              << ": not coloured</li>";
        else
            s << "<li><span class=\"swatch\" style=\"background:" << css_color(stop.color)
              << "\"></span>" << html_escape(stop.label) << "</li>";
    }
    if (no_terrain_data)
        s << "<li><span class=\"swatch nodata\"></span>no terrain data (outside the DEM)</li>";
    s << "</ul></div>";
    return s.str();
}

std::string map_figure_html(const MapFigure& f, const MapOverlay& o) {
    // About 640 px wide leaves room for the legend in a 1000 px column.
    const MapDisplay d = map_display(o.grid, 640.0, 620.0);
    std::ostringstream s;
    s << "<figure class=\"map\" id=\"map-" << html_escape(f.id) << "\"><h3>" << html_escape(f.title)
      << "</h3><div class=\"map-row\"><div class=\"map-frame\" style=\""
      << "width:" << px(d.width) << "px;height:" << px(d.height) << "px\">";
    if (f.png.empty())
        s << "<p class=\"missing\">The quick-look " << html_escape(f.id)
          << ".png could not be read.</p>";
    else
        s << "<img class=\"map-image\" alt=\"" << html_escape(f.title) << "\" width=\""
          << px(d.width) << "\" height=\"" << px(d.height) << "\" src=\"data:image/png;base64,"
          << base64_encode(f.png) << "\">";
    s << "<svg class=\"overlay\" width=\"" << px(d.width) << "\" height=\"" << px(d.height)
      << "\" viewBox=\"0 0 " << px(d.width) << " " << px(d.height) << "\">";
    const std::string outline = outline_path(o.release, o.grid, d.px_per_m);
    if (!outline.empty())
        s << "<path class=\"release\" d=\"" << outline
          << "\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" stroke-dasharray=\"4 2\"/>";
    s << points_svg(o, d) << scale_bar_svg(o, d);
    if (!o.crs_label.empty()) s << north_arrow_svg(d);
    s << "</svg></div>" << legend_html(f.ramp, f.legend_title, o.no_terrain_data)
      << "</div><figcaption>" << html_escape(f.caption) << "</figcaption></figure>";
    return s.str();
}

std::string map_notes_html(const MapOverlay& o) {
    std::ostringstream s;
    s << "<p class=\"note\">How to read the maps: grey is the shaded terrain (light from the "
         "north-west); colour is drawn only where the legend says.";
    if (o.no_terrain_data) s << " " << kNoTerrainDataNote;
    if (!o.release.empty()) s << " The dashed line is the release area.";
    if (!o.points.empty()) s << " White dots are the monitoring points.";
    if (o.crs_label.empty())
        s << " Chute frame: x runs down the chute from left to right and lengths are measured "
             "along the bed; there is no geographic north.";
    else
        s << " Up is grid north of " << html_escape(o.crs_label)
          << " (the arrow); true north differs by the grid convergence of the projection (a "
             "few degrees at most).";
    s << " The scale bar follows from the cell size (" << format_number(o.grid.dx)
      << " m); one coloured square is one computational cell.</p>\n";
    return s.str();
}

}  // namespace avalanche
