#pragma once
// Everything a run needs, as typed values (STYLE.md 5): the scenario file fills it,
// command-line flags override it (defaults < file < flags), validate() checks it once.
// Paths are stored resolved: a scenario file's paths are joined to its folder.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "avalanche/numerics/parameters.hpp"
#include "avalanche/output/output_params.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/material.hpp"
#include "avalanche/physics/release.hpp"

namespace avalanche {

// A real terrain: one or more DEM tiles (mosaicked) in a metric CRS.
struct DemTerrainSpec {
    std::vector<std::string> dem_paths;
    std::string crs;  // e.g. "EPSG:32633"; empty = the DEM's own CRS
};
using TerrainSpec = std::variant<ChuteGeometry, DemTerrainSpec>;

// Release areas as polygons (OGR). Thickness is bed-normal (m); `volume` (m^3)
// scales the thickness so that the released volume matches.
struct PolygonReleaseSpec {
    std::string path;
    std::optional<double> thickness;
    std::string thickness_field;  // attribute holding a per-polygon thickness
    std::optional<double> volume;
};
// Release thickness as a raster (m, bed-normal) on the DEM's grid or resampled to it.
struct RasterReleaseSpec {
    std::string path;
};
using ReleaseSpec = std::variant<ReleaseShape, PolygonReleaseSpec, RasterReleaseSpec>;

// Monitoring points (CSV: name, x, y).
struct PointsSpec {
    std::string path;
    std::string crs;  // empty = the terrain's CRS
};

struct Scenario {
    TerrainSpec terrain = ChuteGeometry{};
    ReleaseSpec release = ReleaseShape{CapRelease{}};
    std::optional<PointsSpec> points;
    MaterialParams material;
    NumericsParams numerics;
    double cell_size = 0.0;  // m; 0 = automatic (DEM resolution); required for the chute
    // Scales the automatic (DEM-resolution) cell size: set by `--quality draft|fine`
    // (app/quality_preset.hpp); an explicit cell size is scaled where it is set instead.
    double cell_size_factor = 1.0;
    OutputParams output;
    std::string source;  // scenario file the values came from, "" for flags only
};

[[nodiscard]] inline bool is_chute(const Scenario& s) {
    return std::holds_alternative<ChuteGeometry>(s.terrain);
}

// Checks the whole scenario with the core validators (material, numerics, chute,
// release, output) plus the combinations only a scenario can get wrong. Throws
// ConfigError naming the scenario key ("numerics.cfl: ...").
void validate(const Scenario& s);

}  // namespace avalanche
