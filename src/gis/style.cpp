// Colour ramps: presets and evaluation (shared by .qml styles and PNG quick-looks).
#include "avalanche/gis/style.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace avalanche::gis {

namespace {

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// Fills empty labels: "0.5 - 1 m", "> 5 m" for classes, "1 m" for the others.
void label_stops(ColorRamp& ramp) {
    const std::string unit = ramp.units.empty() ? "" : " " + ramp.units;
    for (std::size_t k = 0; k < ramp.stops.size(); ++k) {
        ColorStop& s = ramp.stops[k];
        if (!s.label.empty()) continue;
        if (ramp.kind != RampKind::discrete)
            s.label = number(s.value) + unit;
        else if (k + 1 < ramp.stops.size())
            s.label = number(s.value) + " - " + number(ramp.stops[k + 1].value) + unit;
        else
            s.label = "> " + number(s.value) + unit;
    }
}

ColorRamp classes(const std::vector<double>& breaks, const std::vector<Rgba>& palette,
                  const std::string& units) {
    ColorRamp ramp;
    ramp.kind = RampKind::discrete;
    ramp.units = units;
    for (std::size_t k = 0; k < breaks.size(); ++k) {
        // Spread the palette over the classes when their numbers differ.
        const std::size_t c =
            breaks.size() == 1 ? 0 : k * (palette.size() - 1) / (breaks.size() - 1);
        ramp.stops.push_back({breaks[k], palette[c], ""});
    }
    label_stops(ramp);
    return ramp;
}

std::uint8_t mix(std::uint8_t a, std::uint8_t b, double t) {
    return static_cast<std::uint8_t>(std::lround(a + (b - a) * t));
}

}  // namespace

Rgba color_at(const ColorRamp& ramp, double value) {
    const auto& s = ramp.stops;
    if (s.empty() || !std::isfinite(value)) return {0, 0, 0, 0};
    switch (ramp.kind) {
        case RampKind::paletted:
            for (const auto& stop : s)
                if (stop.value == value) return stop.color;
            return {0, 0, 0, 0};
        case RampKind::discrete: {
            if (value <= s.front().value)
                return ramp.draw_below_first ? s.front().color : Rgba{0, 0, 0, 0};
            std::size_t k = 0;
            while (k + 1 < s.size() && value > s[k + 1].value) ++k;
            return s[k].color;
        }
        case RampKind::interpolated: {
            if (value <= s.front().value) return s.front().color;
            if (value >= s.back().value) return s.back().color;
            std::size_t k = 0;
            while (value > s[k + 1].value) ++k;
            const double t = (value - s[k].value) / (s[k + 1].value - s[k].value);
            const Rgba a = s[k].color, b = s[k + 1].color;
            return {mix(a.r, b.r, t), mix(a.g, b.g, t), mix(a.b, b.b, t), mix(a.a, b.a, t)};
        }
    }
    return {0, 0, 0, 0};
}

// Palettes: ColorBrewer sequential schemes (Brewer 2003), readable in print and for
// the common colour-vision deficiencies.
ColorRamp depth_ramp(std::vector<double> breaks_m) {
    return classes(breaks_m,
                   {{198, 219, 239},
                    {158, 202, 225},
                    {107, 174, 214},
                    {49, 130, 189},
                    {8, 81, 156},
                    {8, 48, 107}},
                   "m");
}

ColorRamp velocity_ramp(std::vector<double> breaks_ms) {
    return classes(breaks_ms,
                   {{255, 255, 178}, {254, 204, 92}, {253, 141, 60}, {240, 59, 32}, {189, 0, 38}},
                   "m/s");
}

ColorRamp pressure_ramp(std::vector<double> breaks_kpa) {
    // The hazard limits come beside fixed breaks (1, 10, 100 kPa): limits of 1 and 10 kPa
    // or above 100 must still give increasing classes, each once.
    std::sort(breaks_kpa.begin(), breaks_kpa.end());
    breaks_kpa.erase(std::unique(breaks_kpa.begin(), breaks_kpa.end()), breaks_kpa.end());
    return classes(
        breaks_kpa,
        {{254, 235, 226}, {251, 180, 185}, {247, 104, 161}, {197, 27, 138}, {122, 1, 119}}, "kPa");
}

ColorRamp arrival_time_ramp(double end_time_s) {
    const double end = std::isfinite(end_time_s) && end_time_s > 0 ? end_time_s : 60.0;
    // Round the class width to a whole number of seconds (at least 1 s).
    const double step = std::max(1.0, std::round(end / 6.0));
    std::vector<double> breaks;
    for (int k = 0; k < 6; ++k) breaks.push_back(k * step);
    ColorRamp ramp = classes(breaks,
                             {{255, 255, 204},
                              {199, 233, 180},
                              {127, 205, 187},
                              {65, 182, 196},
                              {44, 127, 184},
                              {37, 52, 148}},
                             "s");
    ramp.draw_below_first = true;  // arrival at t = 0 in the release area
    ramp.stops.front().label = "0 - " + number(step) + " s";
    return ramp;
}

ColorRamp hazard_class_palette(std::vector<std::string> labels) {
    const std::vector<Rgba> colors{
        {255, 255, 255, 0}, {255, 237, 0}, {31, 120, 180}, {227, 26, 28}};
    ColorRamp ramp;
    ramp.kind = RampKind::paletted;
    for (std::size_t k = 0; k < labels.size(); ++k)
        ramp.stops.push_back(
            {static_cast<double>(k), colors[std::min(k, colors.size() - 1)], labels[k]});
    return ramp;
}

}  // namespace avalanche::gis
