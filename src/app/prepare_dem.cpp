// The DEM frame's scene preparation (MODEL.md 3.2): DEM tiles -> metric grid ->
// slope-consistent terrain coefficients; release polygons or raster -> bed-normal
// thickness -> initial state; monitoring points located on the grid.
#include "avalanche/app/prepare_dem.hpp"

#include <omp.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/dem.hpp"
#include "avalanche/gis/points.hpp"
#include "avalanche/gis/release.hpp"
#include "avalanche/io/memory_limit.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"

namespace avalanche {

namespace {

// Bed-normal release thickness per cell, from polygons or a raster.
std::vector<double> release_thickness(const Scenario& s, const gis::Dem& dem, std::vector<std::string>& notes,
                                      std::vector<std::string>& files) {
    if (const auto* poly = std::get_if<PolygonReleaseSpec>(&s.release)) {
        gis::ReleaseOptions opts;
        opts.thickness = poly->thickness;
        opts.thickness_field = poly->thickness_field;
        // Only a volume: rasterize with a unit thickness, scaled below.
        if (!opts.thickness && opts.thickness_field.empty() && poly->volume) opts.thickness = 1.0;
        gis::Release r = gis::rasterize_release_polygons(poly->path, dem.geo, opts);
        gis::check_release_on_valid_dem(r, dem, poly->path);
        notes.push_back(r.description_of_steps);
        files.push_back(poly->path);
        return std::move(r.thickness);
    }
    if (const auto* raster = std::get_if<RasterReleaseSpec>(&s.release)) {
        std::vector<double> t = gis::read_release_raster(raster->path, dem.geo);
        gis::check_release_on_valid_dem(t, dem, raster->path);
        notes.push_back("Read the release thickness raster " + raster->path + ".");
        files.push_back(raster->path);
        return t;
    }
    throw ConfigError("release", "a DEM terrain takes release polygons or a thickness raster, not an analytic shape");
}

// The release's thickness (row-major, nx * ny) as a field written only over the box of
// its released cells, which `box` receives; the rest are untouched zeros
// (field_storage.hpp). Made with a value and copied whole, the field cost two passes of
// writes over every cell (13 M on an ASTER-size tile) for a release of a few.
Field2D thickness_field(const Grid& g, const std::vector<double>& thickness, ActiveBox& box) {
    box = ActiveBox{g.nx, 0, g.ny, 0};
    for (int j = 0; j < g.ny; ++j) {
        const double* row = thickness.data() + static_cast<std::size_t>(j) * g.nx;
        int first = 0;
        while (first < g.nx && row[first] == 0.0) ++first;
        if (first == g.nx) continue;
        int last = g.nx - 1;
        while (row[last] == 0.0) --last;
        box = ActiveBox{std::min(box.i0, first), std::max(box.i1, last + 1), std::min(box.j0, j), j + 1};
    }
    Field2D field(g.nx, g.ny, kGhostLayers);
    if (box.empty()) {
        box = ActiveBox{};
        return field;
    }
    for (int j = box.j0; j < box.j1; ++j) {
        const double* row = thickness.data() + static_cast<std::size_t>(j) * g.nx;
        std::copy(row + box.i0, row + box.i1, field.row(j) + box.i0);
    }
    return field;
}

}  // namespace

PreparedScene prepare_dem_scene(const Scenario& s) {
    const auto& spec = std::get<DemTerrainSpec>(s.terrain);
    PreparedScene p;
    p.frame = Frame::dem;

    gis::DemOptions opts;
    opts.crs = spec.crs;
    opts.cell_size = s.cell_size;
    opts.cell_size_factor = s.cell_size_factor;
    // The grid is refused from the DEM headers if it would not fit (docs/gis.md step 4).
    const MemoryLimit memory = memory_limit();
    opts.max_solver_bytes = memory.bytes;
    opts.memory_limit_source = memory.source;
    opts.solver_bytes_per_cell = kSolverBytesPerCell;
    opts.threads = omp_get_max_threads();
    const gis::Dem dem = gis::load_dem(spec.dem_paths, opts);
    p.input_notes.push_back(dem.description_of_steps);
    p.input_files = spec.dem_paths;
    p.grid = dem.geo.grid;
    p.crs_wkt = dem.geo.crs_wkt;
    p.geotransform = dem.geo.geotransform();
    p.terrain = dem_terrain(p.grid, dem.z, s.numerics.gravity);

    // Release: bed-normal thickness -> vertical thickness of the DEM frame's state.
    std::vector<double> thickness = release_thickness(s, dem, p.input_notes, p.input_files);
    ActiveBox thick;
    const Field2D field = thickness_field(p.grid, thickness, thick);
    thickness = {};  // the field holds it now
    p.initial_box.emplace();
    p.initial = state_at_rest(p.grid, field, p.terrain, thick, &*p.initial_box);
    const ActiveBox& released = *p.initial_box;
    double volume = total_volume(p.initial, p.grid, released);
    if (!(volume > 0.0)) throw ConfigError("release", "the release holds no material on the DEM grid");
    if (const auto* poly = std::get_if<PolygonReleaseSpec>(&s.release); poly && poly->volume) {
        const double scale = *poly->volume / volume;
        for (int j = released.j0; j < released.j1; ++j)
            for (int i = released.i0; i < released.i1; ++i) p.initial.h(i, j) *= scale;
        std::ostringstream n;
        n << "Scaled the release thickness by " << scale << " to the requested volume of " << *poly->volume
          << " m3.";
        p.input_notes.push_back(n.str());
        volume = total_volume(p.initial, p.grid, released);
    }

    // Cells filled outside the DEM's data footprint are not terrain: sinks.
    p.outside_data.assign(p.grid.cells(), 0);
    std::size_t outside = 0;
    for (std::size_t k = 0; k < p.grid.cells(); ++k)
        if (dem.filled_mask[k] == static_cast<std::uint8_t>(gis::CellOrigin::filled_outside)) {
            p.outside_data[k] = 1;
            ++outside;
        }
    if (outside == 0) p.outside_data.clear();

    if (s.points) {
        for (const auto& pt : gis::read_points(s.points->path, s.points->crs, dem.geo))
            p.probes.push_back({pt.name, pt.x, pt.y, pt.i, pt.j});
        p.input_files.push_back(s.points->path);
        p.input_notes.push_back("Located " + std::to_string(p.probes.size()) + " monitoring points from " +
                                s.points->path + ".");
    }

    p.horizontal_position = [grid = p.grid](int i, int j) {
        return std::array<double, 2>{grid.x_center(i), grid.y_center(j)};
    };
    p.cell_area_m2 = p.grid.cell_area();
    std::ostringstream d;
    d << "DEM " << p.grid.nx << " x " << p.grid.ny << " cells of " << p.grid.dx << " m in "
      << dem.geo.crs_label() << (outside ? ", " + std::to_string(outside) + " cells outside the data (sinks)" : "");
    p.description = d.str();
    return p;
}

}  // namespace avalanche
