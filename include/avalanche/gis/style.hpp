#pragma once
// Map styles shared by the QGIS .qml files and the PNG quick-looks, so both show the
// same colours and classes. Presets for the hazard products of MODEL.md section 5.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace avalanche::gis {

struct Rgba {
    std::uint8_t r = 0, g = 0, b = 0, a = 255;
};

struct ColorStop {
    double value = 0.0;  // see RampKind for its meaning
    Rgba color;
    std::string label;  // legend text; "" = generated from the values
};

enum class RampKind {
    // Colours interpolated linearly between stops (QGIS "Interpolated"); values outside
    // take the end colours.
    interpolated,
    // Classes (QGIS "Discrete"): stop k colours values in (value_k, value_k+1], the last
    // stop everything above; values <= the first stop are transparent unless
    // draw_below_first.
    discrete,
    // Exact integer values (QGIS "Paletted / Unique values"), e.g. hazard classes.
    paletted,
};

struct ColorRamp {
    RampKind kind = RampKind::discrete;
    std::vector<ColorStop> stops;   // increasing values
    std::string units;              // appended to generated labels, e.g. "m"
    bool draw_below_first = false;  // discrete: colour values <= first stop with stop 0
};
using QmlStyle = ColorRamp;

// Colour of `value`; alpha 0 when the ramp does not draw it.
Rgba color_at(const ColorRamp& ramp, double value);

// Presets with class breaks (defaults documented in docs/gis.md; pass the scenario's
// thresholds to keep maps and hazard classes consistent).
ColorRamp depth_ramp(std::vector<double> breaks_m = {0.1, 0.5, 1.0, 2.0, 5.0});
ColorRamp velocity_ramp(std::vector<double> breaks_ms = {1.0, 5.0, 10.0, 20.0, 40.0});
// 3 and 30 kPa are the usual avalanche zoning limits.
ColorRamp pressure_ramp(std::vector<double> breaks_kpa = {1.0, 3.0, 10.0, 30.0, 100.0});
// Classes of `end_time_s` / 6, starting at 0 s (release cells).
ColorRamp arrival_time_ramp(double end_time_s);
// 0 none (transparent), 1 low (yellow), 2 medium (blue), 3 high (red): the colours of
// Alpine avalanche hazard zoning.
ColorRamp hazard_class_palette(std::vector<std::string> labels = {"none", "low", "medium", "high"});

// Writes a QGIS layer style (.qml) for a single-band raster: "singlebandpseudocolor"
// for interpolated/discrete ramps, "paletted" for palettes. Put it beside the GeoTIFF
// with the same base name (max_depth.tif + max_depth.qml) and QGIS applies it on
// opening. OutputError on failure.
void write_qml(const std::string& path, const QmlStyle& style);

}  // namespace avalanche::gis
