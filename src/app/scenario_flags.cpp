// The scenario flags of `run` and `batch` (docs/cli.md): one CLI11 option per
// ScenarioOverrides field, named after its scenario key, in the --help group that says
// the precedence (defaults < scenario file < flags).
#include <optional>
#include <sstream>
#include <string>

#include "avalanche/io/enum_names.hpp"
#include "commands.hpp"

namespace avalanche::detail {

namespace {

constexpr const char* kOverrideGroup = "Scenario overrides (defaults < scenario file < flags)";

template <class T>
std::string text(T v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// Adds a flag that fills an optional; the default shown in --help is the built-in one.
template <class T>
void add_override(CLI::App& cmd, const std::string& name, std::optional<T>& target,
                  const std::string& help, const std::string& default_text = "") {
    auto* opt = cmd.add_option_function<T>(
        name, [&target](const T& v) { target = v; }, help);
    opt->group(kOverrideGroup);
    if (!default_text.empty()) opt->default_str(default_text);
}

}  // namespace

void add_scenario_flags(CLI::App& cmd, ScenarioOverrides& o) {
    const MaterialParams m;
    const NumericsParams n;
    cmd.add_option("--dem", o.dem, "DEM file(s) (repeatable); makes a DEM terrain (terrain.dem)")
        ->group(kOverrideGroup);
    add_override(
        cmd, "--release", o.release,
        "Release polygons (.gpkg, .shp, .geojson) or thickness raster (.tif, .tiff, .asc, .vrt)");
    add_override(cmd, "--thickness", o.thickness, "Release thickness, bed-normal (m)");
    add_override(cmd, "--thickness-field", o.thickness_field,
                 "Polygon attribute holding the thickness");
    add_override(cmd, "--volume", o.volume, "Released volume (m^3); scales the thickness");
    add_override(cmd, "--crs", o.crs, "CRS of the DEM, e.g. EPSG:32633 (terrain.crs)");
    add_override(cmd, "--points", o.points, "Monitoring points CSV (points.file)");
    add_override(cmd, "--phi", o.phi, "Internal friction angle (deg)", text(m.phi_deg));
    add_override(cmd, "--delta", o.delta, "Bed friction angle (deg)", text(m.delta_deg));
    add_override(cmd, "--density", o.density, "Bulk density (kg/m^3)", text(m.density));
    add_override(cmd, "--earth-pressure", o.earth_pressure,
                 "Earth pressure model: savage-hutter|isotropic",
                 enum_name(kEarthPressureNames, m.earth_pressure));
    add_override(cmd, "--cell-size", o.cell_size, "Cell size (m); 0 = DEM resolution", "0");
    add_override(cmd, "--t-end", o.t_end, "End time (s)", text(n.t_end));
    add_override(cmd, "--stop-ke-fraction", o.stop_ke_fraction,
                 "Stop when the kinetic energy stays below this fraction of its maximum for "
                 "numerics.stop_duration; 1e-3 ends creeping tails sooner (docs/numerics.md)",
                 text(n.stop_ke_fraction));
    add_override(cmd, "--cfl", o.cfl, "Courant number in (0, 0.5]", text(n.cfl));
    add_override(cmd, "--scheme", o.scheme, "Flux scheme: waf|godunov",
                 enum_name(kSchemeNames, n.scheme));
    add_override(cmd, "--limiter", o.limiter, "WAF limiter: van_leer|superbee|van_albada|minmod",
                 enum_name(kLimiterNames, n.limiter));
    add_override(cmd, "--output-interval", o.output_interval, "Time between snapshots (s)",
                 text(n.output_interval));
    // A switch with its negation, so that a run can turn off what its scenario file
    // turns on; --rest-faces=true|false as batch sweeps spell it.
    cmd.add_flag("--rest-faces,!--no-rest-faces")
        ->description(
            "Faces between cells friction holds at rest pass no mass while below the "
            "Coulomb limit: deposits stay put instead of creeping (numerics.rest_faces; "
            "docs/numerics.md)")
        ->each([&o](const std::string& v) {
            o.rest_faces = parse_switch(v);
            // CLI11 names the flag and passes on only its own errors.
            if (!o.rest_faces) throw CLI::ValidationError(not_a_switch(v));
        })
        ->group(kOverrideGroup);
    add_override(cmd, "--quality", o.quality,
                 "Speed/accuracy preset: draft|standard|fine (docs/performance.md); "
                 "--scheme, --limiter, --cfl, --cell-size win over it",
                 "standard");
}

}  // namespace avalanche::detail
