// What a resumed run checks before it continues: the scenario is rebuilt from the
// effective configuration recorded in the checkpoint (through the scenario-file parser,
// so it is validated like any scenario), and the prepared scene must hash to the
// fingerprint recorded with it (a DEM, release or points file that changed since would
// otherwise silently mix two runs).
#include <cstdio>
#include <cstring>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/io/checkpoint_file.hpp"
#include "avalanche/io/scenario_file.hpp"

namespace avalanche {

namespace {

class Fnv1a {
  public:
    void bytes(const void* data, std::size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t k = 0; k < n; ++k) {
            h_ ^= p[k];
            h_ *= 0x100000001b3ULL;
        }
    }
    template <class T>
    void value(const T& v) {
        bytes(&v, sizeof v);
    }
    // Every cell, ghosts included, row by row: the same values hash the same whether the
    // field stores every row or one (Field2D::same_in_every_row).
    void field(const Field2D& f) {
        value(f.nx());
        value(f.ny());
        value(f.ghosts());
        if (f.empty()) return;
        const int ng = f.ghosts();
        const auto width = static_cast<std::size_t>(f.nx() + 2 * ng);  // not the rows' padding
        for (int j = -ng; j < f.ny() + ng; ++j) words(f.row(j) - ng, width);
    }
    // The values of a grid-sized array, a 64-bit word at a time in four interleaved
    // lanes (word k into lane k % 4), each an FNV-1a step on the whole word followed by
    // a shift-xor that carries its high bits down; the lanes end in the byte-wise hash.
    // Byte by byte, the fifteen fields of a 1756 x 2068 grid took 0.55 s of every run;
    // this takes a few hundredths (docs/performance.md, "Outside the solver").
    void words(const double* data, std::size_t n) {
        std::uint64_t lane[4] = {h_, h_ ^ 1, h_ ^ 2, h_ ^ 3};
        const auto step = [](std::uint64_t h, const double* p) {
            std::uint64_t w;
            std::memcpy(&w, p, sizeof w);
            h = (h ^ w) * 0x100000001b3ULL;
            return h ^ (h >> 32);
        };
        std::size_t k = 0;
        for (; k + 4 <= n; k += 4)
            for (int l = 0; l < 4; ++l) lane[l] = step(lane[l], data + k + l);
        for (; k < n; ++k) lane[0] = step(lane[0], data + k);
        value(n);
        for (const std::uint64_t l : lane) value(l);
    }
    // The cells of box b (clipped to the interior) of a field, row by row.
    void cells(const Field2D& f, const ActiveBox& b) {
        const ActiveBox c = b.clipped(f.nx(), f.ny());
        value(f.nx());
        value(f.ny());
        if (c.empty()) {
            value(0);
            return;
        }
        for (const int v : {c.i0, c.i1, c.j0, c.j1}) value(v);
        for (int j = c.j0; j < c.j1; ++j) words(f.row(j) + c.i0, static_cast<std::size_t>(c.i1 - c.i0));
    }
    [[nodiscard]] std::string hex() const {
        char buf[17];
        std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
        return buf;
    }

  private:
    std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

// A JSON value of the effective configuration as TOML. Doubles with 17 significant
// digits read back bit for bit; JSON string escapes are valid TOML basic strings.
std::string toml_value(const nlohmann::json& v) {
    if (v.is_string()) return v.dump();
    if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
    if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
    if (v.is_number()) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.17g", v.get<double>());
        return buf;
    }
    if (v.is_array()) {
        std::string out = "[";
        for (std::size_t k = 0; k < v.size(); ++k) out += (k ? ", " : "") + toml_value(v[k]);
        return out + "]";
    }
    throw InputError("checkpoint",
                     "unexpected value " + v.dump() + " in the recorded configuration");
}

}  // namespace

std::string scene_fingerprint(const Grid& grid, const TerrainFields& terrain, const State& initial,
                              const ActiveBox& holding, const std::vector<std::uint8_t>& sinks,
                              const std::vector<ProbeLocation>& probes) {
    Fnv1a f;
    f.value(grid.nx);
    f.value(grid.ny);
    f.value(grid.dx);
    f.value(grid.dy);
    f.value(grid.x0);
    f.value(grid.y0);
    f.value(static_cast<int>(terrain.frame));
    // Terrain made on demand (terrain.hpp) holds its coefficients only where a run has
    // needed them so far: it is identified by its elevation and what it derives from it
    // (has_curvature, has_metric), the derivation being fixed by the build (a checkpoint
    // is resumed only by the build that wrote it) and the gravity by the configuration.
    f.value(terrain.on_demand ? 1 : 0);
    f.value(terrain.has_curvature ? 1 : 0);
    f.value(terrain.has_metric ? 1 : 0);
    if (!terrain.on_demand)
        for (const Field2D* field : {&terrain.ax, &terrain.ay, &terrain.px, &terrain.py, &terrain.gn,
                                     &terrain.cxx, &terrain.cxy, &terrain.cyy, &terrain.sx, &terrain.sy,
                                     &terrain.normal_thickness})
            f.field(*field);
    f.field(terrain.elevation);
    for (const Field2D* field : {&initial.h, &initial.hu, &initial.hv}) f.cells(*field, holding);
    f.bytes(sinks.data(), sinks.size());
    for (const ProbeLocation& p : probes) {
        f.bytes(p.name.data(), p.name.size());
        f.value(p.x);
        f.value(p.y);
        f.value(p.i);
        f.value(p.j);
    }
    return f.hex();
}

Scenario scenario_from_config(const nlohmann::json& config, const std::string& label) {
    if (!config.is_object())
        throw InputError(label, "the recorded configuration is not a JSON object");
    std::ostringstream toml;
    for (const auto& [section, values] : config.items()) {
        if (values.is_null()) continue;  // e.g. no [points]
        if (!values.is_object())
            throw InputError(label,
                             "the recorded configuration section " + section + " is not a table");
        toml << "[" << section << "]\n";
        for (const auto& [key, v] : values.items()) {
            if (v.is_null()) continue;  // an optional that was not set
            // Derived settings the scenario file does not take; the config hash that the
            // caller compares covers them.
            if (section == "numerics" && (key == "h_min_relative" || key == "active_margin"))
                continue;
            // Set by --quality on an automatic DEM cell size (Scenario::cell_size_factor),
            // not a scenario-file key: restored below.
            if (section == "numerics" && key == "cell_size_factor") continue;
            toml << key << " = " << toml_value(v) << "\n";
        }
    }
    Scenario s = parse_scenario_text(toml.str(), label, "");
    if (const auto n = config.find("numerics"); n != config.end() && n->contains("cell_size_factor"))
        s.cell_size_factor = (*n)["cell_size_factor"].get<double>();
    validate_with_source(s);
    return s;
}

}  // namespace avalanche
