#pragma once
// Command-line values that override the scenario (defaults < scenario file < flags).
// Each flag has the name of its scenario key (docs/cli.md); an unset optional leaves
// the scenario value alone. No CLI11 here, so the precedence rules are testable alone.
#include <optional>
#include <string>
#include <vector>

#include "avalanche/io/scenario.hpp"

namespace avalanche {

struct ScenarioOverrides {
    std::vector<std::string> dem;        // --dem (repeatable): terrain.dem, makes a DEM terrain
    std::optional<std::string> release;  // --release: polygons, or a raster (.tif/.tiff/.asc/.vrt)
    std::optional<double> thickness;     // --thickness: release.thickness (m)
    std::optional<std::string> thickness_field;  // --thickness-field
    std::optional<double> volume;                // --volume: release.volume (m^3)
    std::optional<std::string> crs;              // --crs: terrain.crs
    std::optional<std::string> points;           // --points: points.file
    std::optional<double> phi;                   // --phi: material.phi_deg
    std::optional<double> delta;                 // --delta: material.delta_deg
    std::optional<double> density;               // --density: material.density
    std::optional<std::string> earth_pressure;   // --earth-pressure
    std::optional<double> cell_size;             // --cell-size: numerics.cell_size
    std::optional<double> t_end;                 // --t-end
    std::optional<double> stop_ke_fraction;      // --stop-ke-fraction
    std::optional<double> cfl;                   // --cfl
    std::optional<std::string> scheme;           // --scheme
    std::optional<std::string> limiter;          // --limiter
    std::optional<double> output_interval;       // --output-interval
    std::optional<bool> rest_faces;              // --rest-faces / --no-rest-faces
    std::optional<std::string> quality;  // --quality draft|standard|fine (before the flags above)
};

// "true" or "false" (an on/off switch given a value: --rest-faces=false, or a batch
// sweep's value); nothing for any other text, which not_a_switch describes.
std::optional<bool> parse_switch(const std::string& value);
std::string not_a_switch(const std::string& value);  // expected true or false, got "value"

// The flag that set scenario key `key` ("material.delta_deg" -> "--delta") in `o`, if
// one did: what a validation error of that key names, and the flag a batch's sweep of
// that key replaces.
std::optional<std::string> flag_for_key(const std::string& key, const ScenarioOverrides& o);

// The flags as a command line would give them, in the order of --help ("--dem a.tif
// --release r.gpkg --thickness 2"; a value with a space or a quote single-quoted): what a
// batch built on flags names as its base. Empty when no flag is set.
std::string overrides_text(const ScenarioOverrides& o);

// Applies the flags; throws ConfigError naming the flag for a bad choice or a flag that
// does not fit the scenario (e.g. --thickness on a cap).
void apply_overrides(Scenario& s, const ScenarioOverrides& o);

// The scenario of a run: the file (if any) < the flags, validated once. A ConfigError
// names the flag when the offending value came from a flag, else the file and its key.
// Without a file, --dem and --release make a DEM scenario.
Scenario assemble_scenario(const std::optional<std::string>& scenario_file,
                           const ScenarioOverrides& o);

}  // namespace avalanche
