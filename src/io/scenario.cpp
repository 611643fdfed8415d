#include "avalanche/io/scenario.hpp"

#include <cmath>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/io/memory_limit.hpp"

namespace avalanche {

namespace {

void validate_terrain(const TerrainSpec& terrain, double cell_size) {
    if (const auto* chute = std::get_if<ChuteGeometry>(&terrain)) {
        validate(*chute);
        // chute_grid refuses a cell size that is not positive or does not divide the chute.
        const Grid g = chute_grid(*chute, cell_size);
        // A chute too fine for the memory would end in std::bad_alloc (exit 70).
        const double cells = static_cast<double>(g.nx) * static_cast<double>(g.ny);
        const MemoryLimit memory = memory_limit();
        if (cells * kSolverBytesPerCell > memory.bytes || cells > 1e9) {
            std::ostringstream msg;
            msg.precision(3);
            msg << "a " << g.nx << " x " << g.ny << " chute grid needs about "
                << cells * kSolverBytesPerCell / (1024.0 * 1024.0 * 1024.0)
                << " GiB of solver state, above the "
                << memory.bytes / (1024.0 * 1024.0 * 1024.0) << " GiB of " << memory.source
                << "; choose a larger cell size";
            throw ConfigError("numerics.cell_size", msg.str());
        }
        return;
    }
    const auto& dem = std::get<DemTerrainSpec>(terrain);
    if (dem.dem_paths.empty()) throw ConfigError("terrain.dem", "expected one or more DEM files");
    for (const auto& p : dem.dem_paths)
        if (p.empty())
            throw ConfigError("terrain.dem", "expected a file name, got an empty string");
}

void validate_release(const ReleaseSpec& release, bool chute) {
    if (const auto* shape = std::get_if<ReleaseShape>(&release)) {
        validate(*shape);
        if (!chute)
            throw ConfigError("release.shape",
                              "a DEM terrain takes release polygons or a "
                              "thickness raster, not an analytic shape");
        return;
    }
    if (const auto* poly = std::get_if<PolygonReleaseSpec>(&release)) {
        if (chute)
            throw ConfigError("release.polygons",
                              "a polygon release needs a DEM terrain (terrain.type = \"dem\")");
        if (poly->path.empty()) throw ConfigError("release.polygons", "expected a file name");
        if (poly->thickness && (!std::isfinite(*poly->thickness) || *poly->thickness <= 0.0))
            throw ConfigError("release.thickness", "expected a positive thickness in metres");
        if (poly->thickness && !poly->thickness_field.empty())
            throw ConfigError("release.thickness",
                              "give either a thickness or a thickness_field, not both");
        if (poly->volume && (!std::isfinite(*poly->volume) || *poly->volume <= 0.0))
            throw ConfigError("release.volume", "expected a positive volume in m^3");
        return;
    }
    const auto& raster = std::get<RasterReleaseSpec>(release);
    if (chute)
        throw ConfigError("release.raster",
                          "a raster release needs a DEM terrain (terrain.type = \"dem\")");
    if (raster.path.empty()) throw ConfigError("release.raster", "expected a file name");
}

}  // namespace

void validate(const Scenario& s) {
    validate(s.material);
    validate(s.numerics);
    validate(s.output);
    if (!std::isfinite(s.cell_size) || s.cell_size < 0.0)
        throw ConfigError("numerics.cell_size", "expected a cell size >= 0 m (0 = automatic)");
    validate_terrain(s.terrain, s.cell_size);
    validate_release(s.release, is_chute(s));
    if (s.points && s.points->path.empty())
        throw ConfigError("points.file", "expected a file name");
    // The chute's grid is in its own frame, not in a CRS the points could be given in.
    if (s.points && is_chute(s))
        throw ConfigError("points.file",
                          "monitoring points need a DEM terrain "
                          "(terrain.type = \"dem\"); the chute has none");
}

}  // namespace avalanche
