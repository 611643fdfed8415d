#include "avalanche/app/scenario_overrides.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <string_view>
#include <type_traits>
#include <utility>

#include "avalanche/app/quality_preset.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/gis/geo_grid.hpp"
#include "avalanche/io/enum_names.hpp"
#include "avalanche/io/scenario_file.hpp"

namespace avalanche {

namespace {

template <class E, std::size_t N>
E parse_choice(const EnumNames<E, N>& names, const std::string& value, const char* flag) {
    if (auto e = enum_from_name(names, value)) return *e;
    throw ConfigError(flag, "expected " + enum_choices(names) + ", got \"" + value + "\"");
}

bool is_raster_file(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".tif" || ext == ".tiff" || ext == ".asc" || ext == ".vrt";
}

void apply_release_overrides(Scenario& s, const ScenarioOverrides& o) {
    if (o.release) {
        if (is_raster_file(*o.release)) {
            s.release = RasterReleaseSpec{*o.release};
        } else {
            // Keep thickness settings of a polygon release from the file; swap the polygons.
            PolygonReleaseSpec p;
            if (const auto* old = std::get_if<PolygonReleaseSpec>(&s.release)) p = *old;
            p.path = *o.release;
            s.release = p;
        }
    }
    auto* polygons = std::get_if<PolygonReleaseSpec>(&s.release);
    if (o.thickness && o.thickness_field)
        throw ConfigError("--thickness", "give either --thickness or --thickness-field, not both");
    if (o.thickness) {
        if (polygons) {
            // The flag wins over the file's thickness field, as every flag over its key.
            polygons->thickness = *o.thickness;
            polygons->thickness_field.clear();
        } else if (auto* shape = std::get_if<ReleaseShape>(&s.release)) {
            if (auto* p = std::get_if<ParaboloidRelease>(shape))
                p->thickness = *o.thickness;
            else if (auto* b = std::get_if<BoxRelease>(shape))
                b->thickness = *o.thickness;
            else
                throw ConfigError("--thickness",
                                  "a cap release has no thickness (its height is its radius)");
        } else {
            throw ConfigError("--thickness", "a raster release holds its own thickness");
        }
    }
    if ((o.thickness_field || o.volume) && !polygons)
        throw ConfigError(o.volume ? "--volume" : "--thickness-field",
                          "applies to a polygon release only (--release FILE.gpkg)");
    if (o.thickness_field) {
        polygons->thickness_field = *o.thickness_field;
        polygons->thickness.reset();  // the flag wins over the file's thickness
    }
    if (o.volume) polygons->volume = *o.volume;
}

// A quality preset (docs/performance.md): scheme, limiter, Courant number, splitting,
// and the cell size scaled -- the scenario's explicit one here, the automatic DEM
// resolution when the DEM is read (Scenario::cell_size_factor). The explicit flags,
// applied after this, win.
void apply_quality(Scenario& s, Quality q) {
    const QualityPreset p = quality_preset(q);
    apply_preset_numerics(p, s.numerics);
    if (s.cell_size > 0.0)
        s.cell_size *= p.cell_size_factor;
    else
        s.cell_size_factor = p.cell_size_factor;
}

}  // namespace

std::optional<std::string> flag_for_key(const std::string& key, const ScenarioOverrides& o) {
    const std::pair<const char*, std::pair<const char*, bool>> table[] = {
        {"terrain.dem", {"--dem", !o.dem.empty()}},
        {"terrain.crs", {"--crs", o.crs.has_value()}},
        {"release.polygons", {"--release", o.release.has_value()}},
        {"release.raster", {"--release", o.release.has_value()}},
        {"release.thickness", {"--thickness", o.thickness.has_value()}},
        {"release.volume", {"--volume", o.volume.has_value()}},
        {"release.thickness_field", {"--thickness-field", o.thickness_field.has_value()}},
        {"points.file", {"--points", o.points.has_value()}},
        {"material.phi_deg", {"--phi", o.phi.has_value()}},
        {"material.delta_deg", {"--delta", o.delta.has_value()}},
        {"material.density", {"--density", o.density.has_value()}},
        {"material.earth_pressure", {"--earth-pressure", o.earth_pressure.has_value()}},
        {"numerics.cell_size", {"--cell-size", o.cell_size.has_value()}},
        {"numerics.cell_size", {"--quality", o.quality.has_value()}},
        {"numerics.t_end", {"--t-end", o.t_end.has_value()}},
        {"numerics.stop_ke_fraction", {"--stop-ke-fraction", o.stop_ke_fraction.has_value()}},
        {"numerics.cfl", {"--cfl", o.cfl.has_value()}},
        {"numerics.scheme", {"--scheme", o.scheme.has_value()}},
        {"numerics.limiter", {"--limiter", o.limiter.has_value()}},
        {"numerics.output_interval", {"--output-interval", o.output_interval.has_value()}},
        {"numerics.rest_faces", {"--rest-faces", o.rest_faces.has_value()}},
    };
    for (const auto& [k, flag] : table)
        if (key == k && flag.second) return std::string(flag.first);
    return std::nullopt;
}

namespace {

// A value as a shell would need it: single-quoted when it holds anything but
// letters, digits and "./_-+=:,@" (a path with a space, a CRS in WKT).
std::string shell_word(const std::string& v) {
    const bool plain = !v.empty() && std::all_of(v.begin(), v.end(), [](unsigned char c) {
        return std::isalnum(c) || std::string_view("./_-+=:,@").find(static_cast<char>(c)) !=
                                      std::string_view::npos;
    });
    if (plain) return v;
    std::string quoted = "'";
    for (char c : v) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::string shortest_number(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

}  // namespace

std::string overrides_text(const ScenarioOverrides& o) {
    std::string out;
    const auto add = [&out](const char* flag, const std::string& value) {
        if (!out.empty()) out += ' ';
        out += flag;
        if (value.empty()) return;
        out += ' ';
        out += shell_word(value);
    };
    const auto text = [&](const char* flag, const auto& v) {
        if (!v) return;
        if constexpr (std::is_same_v<std::decay_t<decltype(*v)>, double>)
            add(flag, shortest_number(*v));
        else
            add(flag, *v);
    };
    for (const auto& d : o.dem) add("--dem", d);
    text("--release", o.release);
    text("--thickness", o.thickness);
    text("--thickness-field", o.thickness_field);
    text("--volume", o.volume);
    text("--crs", o.crs);
    text("--points", o.points);
    text("--phi", o.phi);
    text("--delta", o.delta);
    text("--density", o.density);
    text("--earth-pressure", o.earth_pressure);
    text("--cell-size", o.cell_size);
    text("--t-end", o.t_end);
    text("--stop-ke-fraction", o.stop_ke_fraction);
    text("--cfl", o.cfl);
    text("--scheme", o.scheme);
    text("--limiter", o.limiter);
    text("--output-interval", o.output_interval);
    if (o.rest_faces) add(*o.rest_faces ? "--rest-faces" : "--no-rest-faces", "");
    text("--quality", o.quality);
    return out;
}

std::optional<bool> parse_switch(const std::string& value) {
    if (value == "true") return true;
    if (value == "false") return false;
    return std::nullopt;
}

std::string not_a_switch(const std::string& value) {
    return "expected true or false, got \"" + value + "\"";
}

void apply_overrides(Scenario& s, const ScenarioOverrides& o) {
    if (!o.dem.empty()) {
        DemTerrainSpec dem;
        if (const auto* old = std::get_if<DemTerrainSpec>(&s.terrain)) dem = *old;
        dem.dem_paths = o.dem;
        s.terrain = dem;
    }
    if (o.crs) {
        auto* dem = std::get_if<DemTerrainSpec>(&s.terrain);
        if (!dem)
            throw ConfigError("--crs",
                              "applies to a DEM terrain only (--dem or terrain.type = \"dem\")");
        dem->crs = *o.crs;
    }
    apply_release_overrides(s, o);
    if (o.points) {
        PointsSpec p = s.points.value_or(PointsSpec{});
        p.path = *o.points;
        s.points = p;
    }
    if (o.phi) s.material.phi_deg = *o.phi;
    if (o.delta) s.material.delta_deg = *o.delta;
    if (o.density) s.material.density = *o.density;
    if (o.earth_pressure)
        s.material.earth_pressure =
            parse_choice(kEarthPressureNames, *o.earth_pressure, "--earth-pressure");
    if (o.quality) apply_quality(s, parse_quality(*o.quality, "--quality"));
    if (o.cell_size) s.cell_size = *o.cell_size, s.cell_size_factor = 1.0;
    if (o.t_end) s.numerics.t_end = *o.t_end;
    if (o.stop_ke_fraction) s.numerics.stop_ke_fraction = *o.stop_ke_fraction;
    if (o.cfl) s.numerics.cfl = *o.cfl;
    if (o.scheme) s.numerics.scheme = parse_choice(kSchemeNames, *o.scheme, "--scheme");
    if (o.limiter) s.numerics.limiter = parse_choice(kLimiterNames, *o.limiter, "--limiter");
    if (o.output_interval) s.numerics.output_interval = *o.output_interval;
    if (o.rest_faces) s.numerics.rest_faces = *o.rest_faces;
}

Scenario assemble_scenario(const std::optional<std::string>& scenario_file,
                           const ScenarioOverrides& o) {
    Scenario s;
    if (scenario_file) {
        s = parse_scenario_file(*scenario_file);
    } else {
        if (o.dem.empty())
            throw ConfigError("--scenario",
                              "expected a scenario file, or --dem and --release for a DEM run");
        if (!o.release)
            throw ConfigError("--release", "required with --dem when no --scenario is given");
        s.terrain = DemTerrainSpec{};
        s.release = PolygonReleaseSpec{};
    }
    apply_overrides(s, o);
    try {
        validate(s);
        if (const auto* dem = std::get_if<DemTerrainSpec>(&s.terrain); dem && !dem->crs.empty())
            gis::check_grid_crs(dem->crs, "terrain.crs");
    } catch (const ConfigError& e) {
        const std::string message = e.what();
        const auto colon = message.find(": ");
        const std::string key = message.substr(0, colon);
        if (auto flag = flag_for_key(key, o); flag && colon != std::string::npos)
            throw ConfigError(*flag, message.substr(colon + 2));
        if (!s.source.empty()) throw ConfigError(s.source, message);
        throw;
    }
    return s;
}

}  // namespace avalanche
