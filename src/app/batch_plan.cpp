// Parsing of --sweep values and scenario tables into the cases of a batch.
#include "avalanche/app/batch_plan.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "avalanche/app/scenario_overrides.hpp"
#include "avalanche/core/error.hpp"

namespace avalanche {

namespace {

// What a batch may vary. Material and numerics values only change the time loop, so
// their scenarios share one prepared scene; release thickness and volume change the
// initial state, hence their own preparation. cell_size is absent on purpose: it
// changes the grid, and maps on different grids cannot be compared cell by cell.
constexpr SweepParameter kParameters[] = {
    {"delta", "delta_deg", "material.delta_deg", true, false},
    {"phi", "phi_deg", "material.phi_deg", true, false},
    {"density", "density", "material.density", true, false},
    {"cfl", "cfl", "numerics.cfl", true, false},
    {"t_end", "t_end", "numerics.t_end", true, false},
    {"scheme", "scheme", "numerics.scheme", false, false},
    {"limiter", "limiter", "numerics.limiter", false, false},
    {"earth_pressure", "earth_pressure", "material.earth_pressure", false, false},
    {"rest_faces", "rest_faces", "numerics.rest_faces", false, false},
    {"thickness", "thickness", "release.thickness", true, true},
    {"volume", "volume", "release.volume", true, true},
};

// A range larger than this is almost certainly a typo in the step.
constexpr std::size_t kMaxValuesPerSweep = 10000;

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string item;
    std::istringstream in(s);
    while (std::getline(in, item, sep)) out.push_back(trim(item));
    if (!s.empty() && s.back() == sep) out.emplace_back();
    return out;
}

// Shortest text that reads back as `v`: the same value always gets the same id.
std::string shortest(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

bool parse_number(const std::string& text, double& v) {
    if (text.empty()) return false;
    char* end = nullptr;
    v = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() && std::isfinite(v);
}

// A range value start + k*step carries round-off (0.1 + 2*0.1 = 0.30000000000000004);
// twelve significant digits drop it without touching any value a user would type.
double snap(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    return std::strtod(buf, nullptr);
}

std::vector<std::string> range_values(const std::string& text, const std::string& where) {
    const auto parts = split(text, ':');
    double start = 0, stop = 0, step = 0;
    if (parts.size() != 3 || !parse_number(parts[0], start) || !parse_number(parts[1], stop) ||
        !parse_number(parts[2], step))
        throw ConfigError(where, "expected a range start:stop:step of three numbers");
    if (!(step > 0.0) || stop < start)
        throw ConfigError(where, "expected start <= stop and a positive step");
    // Inclusive: stop counts when it lies within round-off of a step.
    const double steps = std::floor((stop - start) / step + 1e-9);
    if (steps + 1 > static_cast<double>(kMaxValuesPerSweep))
        throw ConfigError(where, "more than " + std::to_string(kMaxValuesPerSweep) + " values");
    std::vector<std::string> out;
    for (int k = 0; k <= static_cast<int>(steps); ++k)
        out.push_back(shortest(snap(start + k * step)));
    return out;
}

std::string canonical_value(const SweepParameter& p, const std::string& text,
                            const std::string& where) {
    if (!p.numeric) {
        if (text.empty()) throw ConfigError(where, std::string("empty value for ") + p.name);
        return text;  // the choice itself is checked when the scenario is validated
    }
    double v = 0;
    if (!parse_number(text, v))
        throw ConfigError(
            where, std::string("expected a number for ") + p.name + ", got \"" + text + "\"");
    return shortest(v);
}

std::string join_names() {
    std::string out;
    for (const auto& p : kParameters) out += (out.empty() ? "" : ", ") + std::string(p.name);
    return out;
}

}  // namespace

const SweepParameter& find_sweep_parameter(const std::string& name, const std::string& where) {
    for (const auto& p : kParameters)
        if (name == p.name || name == p.column) return p;
    if (name == "cell_size")
        throw ConfigError(where,
                          "cell_size cannot be swept: it changes the grid, and the batch compares "
                          "maps cell by cell; run one batch per cell size");
    if (name == "quality")
        throw ConfigError(where,
                          "quality cannot be swept: its presets change the cell size, and the batch "
                          "compares maps cell by cell; run one batch per preset (--quality), or "
                          "sweep scheme, limiter and cfl");
    throw ConfigError(where, "unknown parameter \"" + name + "\"; expected one of " + join_names());
}

Sweep parse_sweep(const std::string& spec) {
    const std::string where = "--sweep " + spec;
    const auto eq = spec.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == spec.size())
        throw ConfigError(where, "expected NAME=v1,v2,... or NAME=start:stop:step");
    Sweep sweep;
    sweep.parameter = &find_sweep_parameter(trim(spec.substr(0, eq)), where);
    const std::string rest = spec.substr(eq + 1);
    if (rest.find(':') != std::string::npos) {
        if (!sweep.parameter->numeric)
            throw ConfigError(where, std::string(sweep.parameter->name) +
                                         " takes a list of "
                                         "choices, not a range");
        sweep.values = range_values(rest, where);
    } else {
        for (const auto& item : split(rest, ','))
            sweep.values.push_back(canonical_value(*sweep.parameter, item, where));
    }
    std::set<std::string> seen;
    for (const auto& v : sweep.values)
        if (!seen.insert(v).second) throw ConfigError(where, "value " + v + " given twice");
    return sweep;
}

std::string case_id(const std::vector<std::pair<const SweepParameter*, std::string>>& values) {
    std::string id;
    for (const auto& [p, v] : values) {
        if (!id.empty()) id += '_';
        id.append(p->name).append("=").append(v);
    }
    for (char& c : id) {
        const bool safe = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
                          (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '=' || c == '+' ||
                          c == '-';
        if (!safe) c = '_';
    }
    return id;
}

std::vector<BatchCase> cartesian_product(const std::vector<Sweep>& sweeps) {
    std::set<std::string> names;
    for (const auto& s : sweeps)
        if (!names.insert(s.parameter->name).second)
            throw ConfigError("--sweep", std::string(s.parameter->name) + " is swept twice");
    std::vector<BatchCase> cases(1);
    for (const auto& s : sweeps) {
        std::vector<BatchCase> next;
        for (const auto& c : cases)
            for (const auto& v : s.values) {
                BatchCase n = c;
                n.values.emplace_back(s.parameter, v);
                next.push_back(std::move(n));
            }
        cases = std::move(next);
    }
    for (auto& c : cases) c.id = case_id(c.values);
    return cases;
}

std::vector<BatchCase> read_case_table(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path, "cannot read the scenario table");
    std::vector<const SweepParameter*> header;
    std::vector<BatchCase> cases;
    std::set<std::string> ids;
    int line_no = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_no;
        const std::string t = trim(line);
        if (t.empty() || t[0] == '#') continue;
        const auto cells = split(t, ',');
        const std::string where = path + ": line " + std::to_string(line_no);
        if (header.empty()) {
            std::set<std::string> names;
            for (const auto& name : cells) {
                header.push_back(&find_sweep_parameter(name, where));
                if (!names.insert(header.back()->name).second)
                    throw ConfigError(where, "column " + name + " given twice");
            }
            continue;
        }
        if (cells.size() != header.size())
            throw InputError(path, "line " + std::to_string(line_no) + " has " +
                                       std::to_string(cells.size()) + " values for " +
                                       std::to_string(header.size()) + " columns");
        BatchCase c;
        for (std::size_t k = 0; k < cells.size(); ++k)
            c.values.emplace_back(header[k], canonical_value(*header[k], cells[k], where));
        c.id = case_id(c.values);
        if (!ids.insert(c.id).second) throw ConfigError(where, "repeats scenario " + c.id);
        cases.push_back(std::move(c));
    }
    if (cases.empty())
        throw InputError(path, "expected a header row and at least one scenario row");
    return cases;
}

std::vector<std::string> flags_replaced_by(const BatchCase& c, const ScenarioOverrides& flags) {
    std::vector<std::string> out;
    for (const auto& [p, v] : c.values)
        if (auto flag = flag_for_key(p->key, flags)) out.push_back(*flag);
    return out;
}

Scenario scenario_for_case(const Scenario& base, const BatchCase& c) {
    ScenarioOverrides o;
    for (const auto& [p, v] : c.values) {
        const std::string name = p->name;
        const double x = p->numeric ? std::strtod(v.c_str(), nullptr) : 0.0;
        if (name == "delta")
            o.delta = x;
        else if (name == "phi")
            o.phi = x;
        else if (name == "density")
            o.density = x;
        else if (name == "cfl")
            o.cfl = x;
        else if (name == "t_end")
            o.t_end = x;
        else if (name == "scheme")
            o.scheme = v;
        else if (name == "limiter")
            o.limiter = v;
        else if (name == "earth_pressure")
            o.earth_pressure = v;
        else if (name == "thickness")
            o.thickness = x;
        else if (name == "volume")
            o.volume = x;
        else if (name == "rest_faces") {
            o.rest_faces = parse_switch(v);
            if (!o.rest_faces)
                throw ConfigError("scenario " + c.id, "rest_faces: " + not_a_switch(v));
        }
    }
    Scenario s = base;
    try {
        apply_overrides(s, o);
        validate(s);
    } catch (const ConfigError& e) {
        throw ConfigError("scenario " + c.id, e.what());
    }
    return s;
}

std::string scene_key(const BatchCase& c) {
    std::string key;
    for (const auto& [p, v] : c.values)
        if (p->changes_scene) key += std::string(p->name) + "=" + v + ";";
    return key;
}

}  // namespace avalanche
