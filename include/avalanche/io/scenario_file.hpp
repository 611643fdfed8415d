#pragma once
// Reading scenario files (TOML, docs/cli.md lists every key). Unknown tables or keys,
// wrong types and bad choices are refused with a ConfigError that names the file and
// the key: "scenario.toml: numerics.cfl: expected a Courant number in (0, 0.5]".
#include <string>

#include "avalanche/io/scenario.hpp"

namespace avalanche {

// Parses and type-checks a scenario file without range checks (the command line may
// still override values); relative paths are resolved against the file's folder.
// Throws InputError if the file cannot be read or is not valid TOML.
Scenario parse_scenario_file(const std::string& path);

// The same from TOML text; `label` names the source in messages and `base_dir`
// resolves relative paths.
Scenario parse_scenario_text(const std::string& text, const std::string& label,
                             const std::string& base_dir);

// parse_scenario_file + validate(), with the file named in every error.
Scenario load_scenario(const std::string& path);

// Runs validate(s) and puts s.source in front of the key of any ConfigError.
void validate_with_source(const Scenario& s);

}  // namespace avalanche
