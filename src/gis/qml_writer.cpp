// QGIS layer styles (.qml) for single-band rasters.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/style.hpp"
#include "avalanche/io/atomic_file.hpp"
#include "avalanche/io/html_text.hpp"  // its five entities are XML's too

namespace avalanche::gis {

namespace {

std::string hex(const Rgba& c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
    return buf;
}

std::string value_text(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    std::ostringstream s;
    s.precision(12);
    s << v;
    return s.str();
}

void item(std::ostream& out, const char* tag, double value, const Rgba& c,
          const std::string& label) {
    out << "          <" << tag << " value=\"" << value_text(value) << "\" color=\"" << hex(c)
        << "\" alpha=\"" << int(c.a) << "\" label=\"" << html_escape(label) << "\"/>\n";
}

// QGIS "Discrete" items are upper bounds (a value takes the first item >= it), so the
// classes (b_k, b_k+1] become items b_k+1, and the last class an item at +inf.
void discrete_items(std::ostream& out, const ColorRamp& r) {
    const auto& s = r.stops;
    if (!r.draw_below_first)
        item(out, "item", s.front().value, {255, 255, 255, 0},
             "below " + value_text(s.front().value) + (r.units.empty() ? "" : " " + r.units));
    for (std::size_t k = 0; k < s.size(); ++k) {
        const double upper = k + 1 < s.size() ? s[k + 1].value : INFINITY;
        item(out, "item", upper, s[k].color, s[k].label);
    }
}

void renderer(std::ostream& out, const ColorRamp& r) {
    const double lo = r.stops.front().value, hi = r.stops.back().value;
    if (r.kind == RampKind::paletted) {
        out << "    <rasterrenderer type=\"paletted\" band=\"1\" opacity=\"1\" "
               "alphaBand=\"-1\" nodataColor=\"\">\n"
               "      <rasterTransparency/>\n"
               "      <colorPalette>\n";
        for (const auto& s : r.stops) item(out, "paletteEntry", s.value, s.color, s.label);
        out << "      </colorPalette>\n"
               "    </rasterrenderer>\n";
        return;
    }
    out << "    <rasterrenderer type=\"singlebandpseudocolor\" band=\"1\" opacity=\"1\" "
           "alphaBand=\"-1\" nodataColor=\"\" classificationMin=\""
        << value_text(lo) << "\" classificationMax=\"" << value_text(hi) << "\">\n"
        << "      <rasterTransparency/>\n"
           "      <minMaxOrigin>\n"
           "        <limits>None</limits>\n"
           "        <extent>WholeRaster</extent>\n"
           "        <statAccuracy>Estimated</statAccuracy>\n"
           "        <cumulativeCutLower>0.02</cumulativeCutLower>\n"
           "        <cumulativeCutUpper>0.98</cumulativeCutUpper>\n"
           "        <stdDevFactor>2</stdDevFactor>\n"
           "      </minMaxOrigin>\n"
           "      <rastershader>\n"
           "        <colorrampshader colorRampType=\""
        << (r.kind == RampKind::discrete ? "DISCRETE" : "INTERPOLATED")
        << "\" classificationMode=\"3\" clip=\"0\" minimumValue=\"" << value_text(lo)
        << "\" maximumValue=\"" << value_text(hi) << "\" labelPrecision=\"4\">\n";
    if (r.kind == RampKind::discrete)
        discrete_items(out, r);
    else
        for (const auto& s : r.stops) item(out, "item", s.value, s.color, s.label);
    out << "        </colorrampshader>\n"
           "      </rastershader>\n"
           "    </rasterrenderer>\n";
}

}  // namespace

void write_qml(const std::string& path, const QmlStyle& style) {
    if (style.stops.empty()) throw OutputError(path, "style has no colour stop");
    std::ostringstream out;
    out << "<!DOCTYPE qgis PUBLIC 'http://mrcc.com/qgis.dtd' 'SYSTEM'>\n"
           "<qgis version=\"3.28.0\" styleCategories=\"AllStyleCategories\">\n"
           "  <pipe>\n";
    renderer(out, style);
    out << "    <brightnesscontrast brightness=\"0\" contrast=\"0\" gamma=\"1\"/>\n"
           "    <huesaturation saturation=\"0\" colorizeOn=\"0\" grayscaleMode=\"0\"/>\n"
           "    <rasterresampler maxOversampling=\"2\"/>\n"
           "  </pipe>\n"
           "  <blendMode>0</blendMode>\n"
           "</qgis>\n";
    // Whole or not at all under its final name, as every product.
    write_file_atomically(path, out.str());
}

}  // namespace avalanche::gis
