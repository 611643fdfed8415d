#pragma once
// The scenarios of a batch (docs/batch.md): parsed from `--sweep NAME=VALUES` (their
// Cartesian product) or from a CSV table (one row per scenario), each turned into a
// validated Scenario by the same overrides as the `run` flags. No CLI11 and no files
// written here, so the parsing rules are testable alone.
#include <string>
#include <utility>
#include <vector>

#include "avalanche/app/scenario_overrides.hpp"
#include "avalanche/io/scenario.hpp"

namespace avalanche {

// A parameter a batch may vary. `column` is its scenario key's bare name (comparison.csv,
// plot names); `changes_scene` says whether the prepared scene (grid, terrain, initial
// state) depends on it, i.e. whether scenarios differing in it need their own preparation.
struct SweepParameter {
    const char* name;    // as in --sweep: "delta"
    const char* column;  // "delta_deg"
    const char* key;     // the scenario key: "material.delta_deg" (flag_for_key)
    bool numeric;        // false: a choice (scheme, earth_pressure, rest_faces), lists only
    bool changes_scene;
};

// The parameter called `name` (its short name or its column name); ConfigError(where)
// naming the sweepable parameters otherwise, with a reason for cell_size.
const SweepParameter& find_sweep_parameter(const std::string& name, const std::string& where);

// One --sweep: a parameter and its values, as canonical text (numbers in their shortest
// round-trip spelling, so "12.50" and "12.5" are the same scenario).
struct Sweep {
    const SweepParameter* parameter = nullptr;
    std::vector<std::string> values;
};

// "delta=10,12.5,15" (a list) or "delta=5:20:2.5" (start:stop:step, stop included when
// it lies on the step within round-off). ConfigError("--sweep <spec>") for bad syntax, an
// unknown parameter, a non-number, a range of a choice, or a repeated value.
Sweep parse_sweep(const std::string& spec);

// One scenario of the batch: its parameter values in sweep (or table column) order.
struct BatchCase {
    std::string id;  // "delta=12.5_phi=30": filesystem-safe, unique within the batch
    std::vector<std::pair<const SweepParameter*, std::string>> values;
};

// The Cartesian product of the sweeps (the first sweep varies slowest). ConfigError if
// a parameter is swept twice.
std::vector<BatchCase> cartesian_product(const std::vector<Sweep>& sweeps);

// A CSV table: a header of parameter names, then one row of values per scenario ('#'
// comments and blank lines skipped). InputError(path) for an unreadable file or a ragged
// row; ConfigError("path: row N ...") for unknown parameters or bad values.
std::vector<BatchCase> read_case_table(const std::string& path);

// The id of a case from its values ("delta=12.5_phi=30"); characters outside
// [A-Za-z0-9._=+-] become '_'.
std::string case_id(const std::vector<std::pair<const SweepParameter*, std::string>>& values);

// The scenario flags of the batch's command line (--delta, --thickness, ...) whose
// parameters the case's values set again, by their flag names: the sweep or table wins
// (defaults < scenario file < flags < the case's values), and the batch says so.
std::vector<std::string> flags_replaced_by(const BatchCase& c, const ScenarioOverrides& flags);

// The base scenario with the case's values applied and validated. ConfigError names the
// case ("scenario delta=40: material.delta_deg: ...") so the user finds the bad value.
Scenario scenario_for_case(const Scenario& base, const BatchCase& c);

// The values of the case that change the prepared scene, as text ("" = the base scene):
// cases with equal keys share one PreparedScene.
std::string scene_key(const BatchCase& c);

}  // namespace avalanche
