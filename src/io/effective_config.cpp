#include "avalanche/io/effective_config.hpp"

#include <cstdint>
#include <cstdio>

#include "avalanche/io/enum_names.hpp"
#include "avalanche_source_hash.hpp"

namespace avalanche {

namespace {

using nlohmann::json;

json terrain_json(const TerrainSpec& terrain) {
    if (const auto* c = std::get_if<ChuteGeometry>(&terrain)) {
        json t{{"type", "chute"},
               {"slope_deg", c->slope_deg},
               {"length", c->length},
               {"width", c->width},
               {"runout_slope_deg", c->runout_slope_deg}};
        if (c->has_transition()) t["transition"] = {*c->transition_start, *c->transition_end};
        return t;
    }
    const auto& d = std::get<DemTerrainSpec>(terrain);
    return {{"type", "dem"}, {"dem", d.dem_paths}, {"crs", d.crs}};
}

struct ShapeJson {
    json operator()(const CapRelease& c) const {
        return {{"shape", "cap"}, {"center", c.center}, {"radius", c.radius}};
    }
    json operator()(const ParaboloidRelease& p) const {
        return {{"shape", "paraboloid"},
                {"center", p.center},
                {"radius", p.radius},
                {"thickness", p.thickness}};
    }
    json operator()(const BoxRelease& b) const {
        return {{"shape", "box"}, {"x", b.x}, {"y", b.y}, {"thickness", b.thickness}};
    }
};

json release_json(const ReleaseSpec& release) {
    if (const auto* shape = std::get_if<ReleaseShape>(&release))
        return std::visit(ShapeJson{}, *shape);
    if (const auto* p = std::get_if<PolygonReleaseSpec>(&release)) {
        json r{{"polygons", p->path}, {"thickness_field", p->thickness_field}};
        r["thickness"] = p->thickness ? json(*p->thickness) : json(nullptr);
        r["volume"] = p->volume ? json(*p->volume) : json(nullptr);
        return r;
    }
    return {{"raster", std::get<RasterReleaseSpec>(release).path}};
}

json numerics_json(const NumericsParams& n, double cell_size) {
    return {{"cell_size", cell_size},
            {"scheme", enum_name(kSchemeNames, n.scheme)},
            {"limiter", enum_name(kLimiterNames, n.limiter)},
            {"splitting", enum_name(kSplittingNames, n.splitting)},
            {"boundary", enum_name(kBoundaryNames, n.boundary)},
            {"cfl", n.cfl},
            {"t_end", n.t_end},
            {"output_interval", n.output_interval},
            {"h_min", n.h_min},
            {"h_min_relative", n.h_min_relative},
            {"source_substeps", n.source_substeps},
            {"rest_faces", n.rest_faces},
            {"stop_ke_fraction", n.stop_ke_fraction},
            {"stop_duration", n.stop_duration},
            {"active_margin", n.active_margin},
            {"gravity", n.gravity}};
}

}  // namespace

json effective_config(const Scenario& s) {
    json config;
    config["terrain"] = terrain_json(s.terrain);
    config["release"] = release_json(s.release);
    config["material"] = {
        {"phi_deg", s.material.phi_deg},
        {"delta_deg", s.material.delta_deg},
        {"earth_pressure", enum_name(kEarthPressureNames, s.material.earth_pressure)},
        {"density", s.material.density}};
    config["numerics"] = numerics_json(s.numerics, s.cell_size);
    // Recorded only when a quality preset scales the automatic cell size, so that the
    // configuration hashes of earlier runs stay valid.
    if (s.cell_size_factor != 1.0) config["numerics"]["cell_size_factor"] = s.cell_size_factor;
    config["points"] =
        s.points ? json{{"file", s.points->path}, {"crs", s.points->crs}} : json(nullptr);
    config["output"] = {{"h_threshold", s.output.h_threshold},
                        {"pressure_high_kpa", s.output.pressure_high_kpa},
                        {"pressure_low_kpa", s.output.pressure_low_kpa}};
    return config;
}

std::string config_hash(const json& config) {
    // FNV-1a: tiny, stable across platforms and releases; collisions are harmless here
    // (the hash labels results, it does not secure them).
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : config.dump()) {
        h ^= c;
        h *= 0x100000001b3ULL;
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

std::string config_hash_without_paths(json config) {
    // Each path becomes "" (a list of DEM tiles keeps its length).
    const auto blank = [&](const char* section, const char* key) {
        if (!config.contains(section) || !config[section].is_object() || !config[section].contains(key))
            return;
        nlohmann::json& v = config[section][key];
        if (v.is_array())
            for (auto& path : v) path = "";
        else if (v.is_string())
            v = "";
    };
    blank("terrain", "dem");
    blank("release", "polygons");
    blank("release", "raster");
    blank("points", "file");
    return config_hash(config);
}

std::string software_version() { return AVALANCHE_VERSION; }

std::string source_hash() { return AVALANCHE_SOURCE_HASH; }

}  // namespace avalanche
