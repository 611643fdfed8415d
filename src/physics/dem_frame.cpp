#include "avalanche/physics/dem_frame.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "avalanche/core/error.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/physics/dem_coefficients.hpp"

namespace avalanche {

namespace {

// First and second derivatives of z at cell (i, j) by finite differences. Each is
// written so that mirroring the DEM in x or y gives the mirrored derivative to the
// bit: the two outer values of a second difference are added before the centre is
// taken off, and the mixed difference adds its diagonal pairs before subtracting, so
// no sum depends on which side comes first (a mirrored scene then gives the mirrored
// run to the bit; test_random_extremes.cpp).
struct Derivatives {
    double zx, zy, zxx, zxy, zyy;
};

// z is the terrain's elevation field, read at clamped interior cells only (its ghosts
// are not part of the DEM).
Derivatives derivatives_at(const Grid& g, const Field2D& z, int i, int j) {
    const auto at = [&](int ii, int jj) {
        return z(std::clamp(ii, 0, g.nx - 1), std::clamp(jj, 0, g.ny - 1));
    };
    Derivatives d{};
    // x: central inside, one-sided at the edges; a single column has no slope.
    if (g.nx >= 3) {
        const int ic = std::clamp(i, 1, g.nx - 2);  // second differences from the nearest interior
        d.zxx = ((at(ic + 1, j) + at(ic - 1, j)) - 2.0 * at(ic, j)) / (g.dx * g.dx);
    }
    if (g.nx >= 2) {
        const int il = std::max(i - 1, 0), ir = std::min(i + 1, g.nx - 1);
        d.zx = (at(ir, j) - at(il, j)) / ((ir - il) * g.dx);
    }
    if (g.ny >= 3) {
        const int jc = std::clamp(j, 1, g.ny - 2);
        d.zyy = ((at(i, jc + 1) + at(i, jc - 1)) - 2.0 * at(i, jc)) / (g.dy * g.dy);
    }
    if (g.ny >= 2) {
        const int jl = std::max(j - 1, 0), jr = std::min(j + 1, g.ny - 1);
        d.zy = (at(i, jr) - at(i, jl)) / ((jr - jl) * g.dy);
    }
    if (g.nx >= 2 && g.ny >= 2) {
        const int il = std::max(i - 1, 0), ir = std::min(i + 1, g.nx - 1);
        const int jl = std::max(j - 1, 0), jr = std::min(j + 1, g.ny - 1);
        d.zxy = ((at(ir, jr) + at(il, jl)) - (at(il, jr) + at(ir, jl))) /
                ((ir - il) * g.dx * (jr - jl) * g.dy);
    }
    return d;
}

// Whether a cell's second differences are all within the tolerance: a plane's are
// round-off (~1e-13 z/dx^2), its curvature is taken for an exact 0.
bool planar_at(const Derivatives& d, double tolerance) {
    return !(std::max({std::abs(d.zxx), std::abs(d.zxy), std::abs(d.zyy)}) > tolerance);
}

// Is any cell not planar (planar_at)? Planar terrain skips the centripetal term. The
// scan stops at the first such cell (on a real DEM, in its first rows); only a plane is
// read to the end.
bool has_curvature(const Grid& g, const Field2D& z, double tolerance) {
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            if (!planar_at(derivatives_at(g, z, i, j), tolerance)) return true;
    return false;
}

// Copies the edge values of cells [i0, i1) x [j0, j1) into the ghost cells beyond the
// edges of the grid the range reaches: Field2D::extend_to_ghosts restricted to the
// range (columns first, then rows with their corners), so the values are the same.
void extend_to_ghosts_of(Field2D& f, int i0, int i1, int j0, int j1) {
    const int nx = f.nx(), ny = f.ny(), ng = f.ghosts();
    for (int j = j0; j < j1; ++j)
        for (int g = 1; g <= ng; ++g) {
            if (i0 == 0) f(-g, j) = f(0, j);
            if (i1 == nx) f(nx - 1 + g, j) = f(nx - 1, j);
        }
    const int ia = i0 == 0 ? -ng : i0, ib = i1 == nx ? nx + ng : i1;
    for (int g = 1; g <= ng; ++g)
        for (int i = ia; i < ib; ++i) {
            if (j0 == 0) f(i, -g) = f(i, 0);
            if (j1 == ny) f(i, ny - 1 + g) = f(i, ny - 1);
        }
}

// The mean of f over cell (i, j) and its eight neighbours in the grid. The values are
// added in mirror pairs (north with south, east with west, each diagonal with its
// opposite), so that the sum of a mirrored field is the same to the bit; a neighbour
// outside the grid adds an exact 0 and is not counted.
template <class F>
double mean_of_neighbours(const Grid& grid, const F& f, int i, int j) {
    int n = 0;
    const auto value = [&](int di, int dj) {
        const int ii = i + di, jj = j + dj;
        if (ii < 0 || jj < 0 || ii >= grid.nx || jj >= grid.ny) return 0.0;
        ++n;
        return f(ii, jj);
    };
    const double sides = (value(0, 1) + value(0, -1)) + (value(1, 0) + value(-1, 0));
    const double corners = (value(1, 1) + value(-1, -1)) + (value(-1, 1) + value(1, -1));
    return (value(0, 0) + (sides + corners)) / n;
}

// The DEM frame's coefficients of the cells [i0, i1) x [j0, j1), from t.elevation.
// The smoothed curvature of a cell is the mean of the raw curvature of its neighbours
// in the grid (mean_of_neighbours), summed in the same order as over the whole grid at once; the
// raw curvature is computed in the same pass as the other coefficients, over the range and the one
// cell around it the smoothing reads (each cell's derivatives once).
void make_dem_cells(TerrainFields& t, const Grid& grid, double gravity, const DemFrameOptions& options,
                    int i0, int i1, int j0, int j1) {
    const int m = t.has_curvature && options.smooth_curvature ? 1 : 0;
    const int a0 = std::max(0, i0 - m), a1 = std::min(grid.nx, i1 + m);
    const int b0 = std::max(0, j0 - m), b1 = std::min(grid.ny, j1 + m);
    const int w = a1 - a0;
    std::vector<double> raw[3];
    if (t.has_curvature)
        for (auto& r : raw) r.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(b1 - b0));
    for (int j = b0; j < b1; ++j) {
        for (int i = a0; i < a1; ++i) {
            const Derivatives dd = derivatives_at(grid, t.elevation, i, j);
            const double s2 = 1.0 + dd.zx * dd.zx + dd.zy * dd.zy;
            const double s = std::sqrt(s2);
            if (t.has_curvature) {
                // A planar cell's curvature is an exact 0, not the round-off of a
                // plane's differences: else whether a plane's cells carry that round-off
                // into the load would depend on a cliff anywhere else in the grid (which
                // makes has_curvature true), and a run on a DEM would differ, to the bit,
                // from the same run on a crop of it without the cliff.
                const bool planar = planar_at(dd, options.curvature_tolerance);
                const std::size_t k = static_cast<std::size_t>(j - b0) * w + (i - a0);
                raw[0][k] = planar ? 0.0 : dd.zxx / s;
                raw[1][k] = planar ? 0.0 : dd.zxy / s;
                raw[2][k] = planar ? 0.0 : dd.zyy / s;
            }
            if (i < i0 || i >= i1 || j < j0 || j >= j1) continue;  // the smoothing's halo
            // ax, ay, px, py and gn are not stored: their readers compute them from sx, sy
            // (TerrainFields::coefficients).
            t.sx(i, j) = dd.zx;
            t.sy(i, j) = dd.zy;
            t.normal_thickness(i, j) = dem_coefficients(dd.zx, dd.zy, gravity).normal_thickness;
        }
    }
    if (t.has_curvature) {
        Field2D* out[3] = {&t.cxx, &t.cxy, &t.cyy};
        for (int c = 0; c < 3; ++c) {
            const auto at = [&](int i, int j) { return raw[c][static_cast<std::size_t>(j - b0) * w + (i - a0)]; };
            for (int j = j0; j < j1; ++j)
                for (int i = i0; i < i1; ++i) {
                    if (m == 0) {
                        (*out[c])(i, j) = at(i, j);
                        continue;
                    }
                    (*out[c])(i, j) = mean_of_neighbours(grid, at, i, j);
                }
        }
    }
    for (Field2D TerrainFields::*f : kDerivedTerrainFields)
        if (!(t.*f).empty()) extend_to_ghosts_of(t.*f, i0, i1, j0, j1);
}

}  // namespace

TerrainFields dem_terrain(const Grid& grid, const std::vector<double>& z, double gravity,
                          const DemFrameOptions& options) {
    if (z.size() != grid.cells())
        throw Error(ExitCode::internal, "dem_terrain: elevation size does not match the grid");
    TerrainFields t;
    t.frame = Frame::dem;
    const auto field = [&] { return Field2D(grid.nx, grid.ny, kGhostLayers); };
    t.elevation = field();
    t.elevation.advise_written_whole();
    t.elevation.set_interior(z);
    t.elevation.extend_to_ghosts();
    t.has_curvature = has_curvature(grid, t.elevation, options.curvature_tolerance);
    t.has_metric = true;
    t.slope_gravity = gravity;
    // Zero until made (Field2D's zeros are not written: memory nobody makes stays
    // untouched).
    const auto curvature = [](Field2D TerrainFields::*f) {
        return f == &TerrainFields::cxx || f == &TerrainFields::cxy || f == &TerrainFields::cyy;
    };
    // Not stored: functions of sx, sy (TerrainFields::coefficients).
    const auto from_slopes = [](Field2D TerrainFields::*f) {
        return f == &TerrainFields::ax || f == &TerrainFields::ay || f == &TerrainFields::px ||
               f == &TerrainFields::py || f == &TerrainFields::gn;
    };
    for (Field2D TerrainFields::*f : kDerivedTerrainFields)
        if ((t.has_curvature || !curvature(f)) && !from_slopes(f)) t.*f = field();
    t.on_demand = std::make_unique<TerrainTiles>(
        grid, [grid, gravity, options](TerrainFields& f, int i0, int i1, int j0, int j1) {
            make_dem_cells(f, grid, gravity, options, i0, i1, j0, j1);
        });
    if (!options.on_demand) {
        for (Field2D TerrainFields::*f : kDerivedTerrainFields) (t.*f).advise_written_whole();
        t.ensure_everywhere();
        t.on_demand.reset();
    }
    return t;
}

}  // namespace avalanche
