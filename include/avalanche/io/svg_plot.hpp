#pragma once
// A minimal SVG line plot (axes, ticks, one polyline with markers per series, legend):
// enough to see a trend such as runout vs friction angle in any browser, without a
// plotting dependency.
#include <string>
#include <vector>

namespace avalanche {

struct PlotSeries {
    std::string label;  // legend text; "" = no legend entry
    std::vector<double> x, y;
};

struct LinePlot {
    std::string title, x_label, y_label;
    std::vector<PlotSeries> series;
};

// The plot as an SVG document. Non-finite points are skipped; an empty plot still gives
// valid SVG with axes.
std::string svg_line_plot(const LinePlot& plot);

}  // namespace avalanche
