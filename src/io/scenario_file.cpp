#include "avalanche/io/scenario_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "toml_section.hpp"

namespace avalanche {

namespace {

using detail::TomlSection;
namespace fs = std::filesystem;

std::string resolve(const std::string& base_dir, const std::string& path) {
    if (path.empty() || base_dir.empty() || fs::path(path).is_absolute()) return path;
    return (fs::path(base_dir) / path).lexically_normal().string();
}

const toml::table* subtable(const toml::table& root, const char* name, const std::string& label) {
    const toml::node* n = root.get(name);
    if (!n) return nullptr;
    if (!n->is_table())
        throw ConfigError(label + ": " + name, "expected a table [" + std::string(name) +
                                                   "], got " + detail::describe_type(*n));
    return n->as_table();
}

ChuteGeometry parse_chute(TomlSection& t) {
    ChuteGeometry c;
    if (auto v = t.number("slope_deg")) c.slope_deg = *v;
    if (auto v = t.number("length")) c.length = *v;
    if (auto v = t.number("width")) c.width = *v;
    if (auto v = t.pair("transition")) {
        c.transition_start = (*v)[0];
        c.transition_end = (*v)[1];
    }
    if (auto v = t.number("runout_slope_deg")) c.runout_slope_deg = *v;
    t.refuse_unread_keys(
        "type = \"chute\" takes slope_deg, length, width, transition, runout_slope_deg");
    return c;
}

TerrainSpec parse_terrain(TomlSection& t, const std::string& base_dir) {
    if (!t.present())
        t.fail("type", "missing: a scenario needs [terrain] with type = \"chute\" or \"dem\"");
    const auto type = t.text("type");
    if (!type) t.fail("type", "missing: expected \"chute\" or \"dem\"");
    if (*type == "chute") return parse_chute(t);
    if (*type != "dem") t.fail("type", "expected \"chute\" or \"dem\", got \"" + *type + "\"");
    DemTerrainSpec dem;
    if (auto v = t.text_or_list("dem"))
        for (const auto& p : *v) dem.dem_paths.push_back(resolve(base_dir, p));
    if (auto v = t.text("crs")) dem.crs = *v;
    t.refuse_unread_keys("type = \"dem\" takes dem, crs");
    return dem;
}

ReleaseShape parse_shape(TomlSection& r, const std::string& shape) {
    const auto required_number = [&](const char* key) {
        auto v = r.number(key);
        if (!v) r.fail(key, "missing: shape = \"" + shape + "\" needs it");
        return *v;
    };
    const auto required_pair = [&](const char* key) {
        auto v = r.pair(key);
        if (!v) r.fail(key, "missing: shape = \"" + shape + "\" needs it");
        return *v;
    };
    ReleaseShape out;
    if (shape == "cap") {
        out = CapRelease{required_pair("center"), required_number("radius")};
        r.refuse_unread_keys("shape = \"cap\" takes center, radius");
    } else if (shape == "paraboloid") {
        ParaboloidRelease p;
        p.center = required_pair("center");
        p.radius = required_number("radius");
        p.thickness = required_number("thickness");
        out = p;
        r.refuse_unread_keys("shape = \"paraboloid\" takes center, radius, thickness");
    } else if (shape == "box") {
        BoxRelease b;
        b.x = required_pair("x");
        b.y = required_pair("y");
        b.thickness = required_number("thickness");
        out = b;
        r.refuse_unread_keys("shape = \"box\" takes x, y, thickness");
    } else {
        r.fail("shape", "expected one of \"cap\", \"paraboloid\", \"box\", got \"" + shape + "\"");
    }
    return out;
}

ReleaseSpec parse_release(TomlSection& r, const std::string& base_dir) {
    if (!r.present()) r.fail("shape", "missing: a scenario needs a [release] table");
    const bool has_shape = r.has("shape"), has_polygons = r.has("polygons"),
               has_raster = r.has("raster");
    if (has_shape + has_polygons + has_raster != 1)
        r.fail("shape", "expected exactly one of shape, polygons or raster");
    if (has_shape) return parse_shape(r, *r.text("shape"));
    if (has_raster) {
        RasterReleaseSpec spec{resolve(base_dir, *r.text("raster"))};
        r.refuse_unread_keys("a raster release takes raster only");
        return spec;
    }
    PolygonReleaseSpec p;
    p.path = resolve(base_dir, *r.text("polygons"));
    p.thickness = r.number("thickness");
    if (auto v = r.text("thickness_field")) p.thickness_field = *v;
    p.volume = r.number("volume");
    r.refuse_unread_keys("a polygon release takes polygons, thickness, thickness_field, volume");
    return p;
}

MaterialParams parse_material(TomlSection& m) {
    MaterialParams p;
    if (auto v = m.number("phi_deg")) p.phi_deg = *v;
    if (auto v = m.number("delta_deg")) p.delta_deg = *v;
    if (auto v = m.choice("earth_pressure", kEarthPressureNames)) p.earth_pressure = *v;
    if (auto v = m.number("density")) p.density = *v;
    m.refuse_unread_keys("[material] takes phi_deg, delta_deg, earth_pressure, density");
    return p;
}

int to_int(TomlSection& t, const char* key, std::int64_t v) {
    if (v < -1000000000 || v > 1000000000) t.fail(key, "expected a moderate integer");
    return static_cast<int>(v);
}

NumericsParams parse_numerics(TomlSection& n, double& cell_size) {
    NumericsParams p;
    if (auto v = n.number("cell_size")) cell_size = *v;
    if (auto v = n.choice("scheme", kSchemeNames)) p.scheme = *v;
    if (auto v = n.choice("limiter", kLimiterNames)) p.limiter = *v;
    if (auto v = n.number("cfl")) p.cfl = *v;
    if (auto v = n.number("t_end")) p.t_end = *v;
    if (auto v = n.number("output_interval")) p.output_interval = *v;
    if (auto v = n.number("h_min")) p.h_min = *v;
    if (auto v = n.choice("boundary", kBoundaryNames)) p.boundary = *v;
    if (auto v = n.integer("source_substeps")) p.source_substeps = to_int(n, "source_substeps", *v);
    if (auto v = n.number("stop_ke_fraction")) p.stop_ke_fraction = *v;
    if (auto v = n.number("stop_duration")) p.stop_duration = *v;
    if (auto v = n.choice("splitting", kSplittingNames)) p.splitting = *v;
    if (auto v = n.number("gravity")) p.gravity = *v;
    if (auto v = n.boolean("rest_faces")) p.rest_faces = *v;
    n.refuse_unread_keys(
        "[numerics] takes cell_size, scheme, limiter, cfl, t_end, output_interval, h_min, "
        "boundary, source_substeps, stop_ke_fraction, stop_duration, splitting, gravity, "
        "rest_faces");
    return p;
}

std::optional<PointsSpec> parse_points(TomlSection& t, const std::string& base_dir) {
    if (!t.present()) return std::nullopt;
    PointsSpec p;
    const auto file = t.text("file");
    if (!file) t.fail("file", "missing: [points] needs file = \"points.csv\"");
    p.path = resolve(base_dir, *file);
    if (auto v = t.text("crs")) p.crs = *v;
    t.refuse_unread_keys("[points] takes file, crs");
    return p;
}

OutputParams parse_output(TomlSection& t) {
    OutputParams o;
    if (auto v = t.number("h_threshold")) o.h_threshold = *v;
    if (auto v = t.number("pressure_high_kpa")) o.pressure_high_kpa = *v;
    if (auto v = t.number("pressure_low_kpa")) o.pressure_low_kpa = *v;
    t.refuse_unread_keys("[output] takes h_threshold, pressure_high_kpa, pressure_low_kpa");
    return o;
}

Scenario parse_table(const toml::table& root, const std::string& label,
                     const std::string& base_dir) {
    static const std::set<std::string, std::less<>> kTables{"terrain",  "release", "material",
                                                            "numerics", "points",  "output"};
    for (const auto& [key, node] : root)
        if (!kTables.count(key.str()))
            throw ConfigError(label + ": " + detail::printable(key.str()),
                              "unknown table or key (a scenario has [terrain], [release], "
                              "[material], [numerics], [points], [output])");
    const auto section = [&](const char* name) {
        return TomlSection(subtable(root, name, label), name, label);
    };
    Scenario s;
    s.source = label;
    auto terrain = section("terrain");
    s.terrain = parse_terrain(terrain, base_dir);
    auto release = section("release");
    s.release = parse_release(release, base_dir);
    auto material = section("material");
    s.material = parse_material(material);
    auto numerics = section("numerics");
    s.numerics = parse_numerics(numerics, s.cell_size);
    auto points = section("points");
    s.points = parse_points(points, base_dir);
    auto output = section("output");
    s.output = parse_output(output);
    return s;
}

}  // namespace

Scenario parse_scenario_text(const std::string& text, const std::string& label,
                             const std::string& base_dir) {
    toml::table root;
    try {
        root = toml::parse(text, label);
    } catch (const toml::parse_error& e) {
        // The description quotes the offending bytes, newlines included.
        throw InputError(label, "line " + std::to_string(e.source().begin.line) + ": " +
                                    detail::printable(e.description()));
    }
    return parse_table(root, label, base_dir);
}

Scenario parse_scenario_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path, "cannot open the scenario file");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_scenario_text(text.str(), path, fs::path(path).parent_path().string());
}

void validate_with_source(const Scenario& s) {
    try {
        validate(s);
    } catch (const ConfigError& e) {
        if (s.source.empty()) throw;
        throw ConfigError(s.source, e.what());
    }
}

Scenario load_scenario(const std::string& path) {
    Scenario s = parse_scenario_file(path);
    validate_with_source(s);
    return s;
}

}  // namespace avalanche
