#include "avalanche/physics/dem_frame.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "avalanche/core/error.hpp"
#include "avalanche/core/state.hpp"

namespace avalanche {

namespace {

// First and second derivatives of z at cell (i, j) by finite differences.
struct Derivatives {
    double zx, zy, zxx, zxy, zyy;
};

Derivatives derivatives_at(const Grid& g, const std::vector<double>& z, int i, int j) {
    const auto at = [&](int ii, int jj) {
        ii = std::clamp(ii, 0, g.nx - 1);
        jj = std::clamp(jj, 0, g.ny - 1);
        return z[static_cast<std::size_t>(jj) * g.nx + ii];
    };
    Derivatives d{};
    // x: central inside, one-sided at the edges; a single column has no slope.
    if (g.nx >= 3) {
        const int ic = std::clamp(i, 1, g.nx - 2);  // second differences from the nearest interior
        d.zxx = (at(ic + 1, j) - 2.0 * at(ic, j) + at(ic - 1, j)) / (g.dx * g.dx);
    }
    if (g.nx >= 2) {
        const int il = std::max(i - 1, 0), ir = std::min(i + 1, g.nx - 1);
        d.zx = (at(ir, j) - at(il, j)) / ((ir - il) * g.dx);
    }
    if (g.ny >= 3) {
        const int jc = std::clamp(j, 1, g.ny - 2);
        d.zyy = (at(i, jc + 1) - 2.0 * at(i, jc) + at(i, jc - 1)) / (g.dy * g.dy);
    }
    if (g.ny >= 2) {
        const int jl = std::max(j - 1, 0), jr = std::min(j + 1, g.ny - 1);
        d.zy = (at(i, jr) - at(i, jl)) / ((jr - jl) * g.dy);
    }
    if (g.nx >= 2 && g.ny >= 2) {
        const int il = std::max(i - 1, 0), ir = std::min(i + 1, g.nx - 1);
        const int jl = std::max(j - 1, 0), jr = std::min(j + 1, g.ny - 1);
        d.zxy = (at(ir, jr) - at(il, jr) - at(ir, jl) + at(il, jl)) / ((ir - il) * g.dx * (jr - jl) * g.dy);
    }
    return d;
}

Field2D smoothed(const Field2D& f, const Grid& g) {
    Field2D out(g.nx, g.ny, kGhostLayers, 0.0);
    for (int j = 0; j < g.ny; ++j) {
        for (int i = 0; i < g.nx; ++i) {
            double sum = 0.0;
            int n = 0;
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int ii = i + di, jj = j + dj;
                    if (ii < 0 || jj < 0 || ii >= g.nx || jj >= g.ny) continue;
                    sum += f(ii, jj);
                    ++n;
                }
            out(i, j) = sum / n;
        }
    }
    return out;
}

}  // namespace

TerrainFields dem_terrain(const Grid& grid, const std::vector<double>& z, double gravity,
                          const DemFrameOptions& options) {
    if (z.size() != grid.cells())
        throw Error(ExitCode::internal, "dem_terrain: elevation size does not match the grid");
    // First pass: is there any curvature at all? Planar terrain skips the term. The
    // derivatives are computed again in the second pass rather than kept: kept, they
    // were 40 bytes per cell on top of the terrain fields and set the run's peak memory.
    double max_curvature = 0.0;
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const Derivatives dd = derivatives_at(grid, z, i, j);
            max_curvature = std::max({max_curvature, std::abs(dd.zxx), std::abs(dd.zxy), std::abs(dd.zyy)});
        }
    TerrainFields t;
    t.frame = Frame::dem;
    t.allocate(grid, max_curvature > options.curvature_tolerance, /*metric=*/true);
    for (int j = 0; j < grid.ny; ++j) {
        for (int i = 0; i < grid.nx; ++i) {
            const Derivatives dd = derivatives_at(grid, z, i, j);
            const double s2 = 1.0 + dd.zx * dd.zx + dd.zy * dd.zy;
            const double s = std::sqrt(s2);
            t.ax(i, j) = -gravity * dd.zx / s2;
            t.ay(i, j) = -gravity * dd.zy / s2;
            t.px(i, j) = gravity / (s2 * (1.0 + dd.zx * dd.zx));
            t.py(i, j) = gravity / (s2 * (1.0 + dd.zy * dd.zy));
            t.gn(i, j) = gravity / s;
            t.sx(i, j) = dd.zx;
            t.sy(i, j) = dd.zy;
            t.normal_thickness(i, j) = 1.0 / s;
            t.elevation(i, j) = z[static_cast<std::size_t>(j) * grid.nx + i];
            if (t.has_curvature) {
                t.cxx(i, j) = dd.zxx / s;
                t.cxy(i, j) = dd.zxy / s;
                t.cyy(i, j) = dd.zyy / s;
            }
        }
    }
    if (t.has_curvature && options.smooth_curvature) {
        t.cxx = smoothed(t.cxx, grid);
        t.cxy = smoothed(t.cxy, grid);
        t.cyy = smoothed(t.cyy, grid);
    }
    t.extend_to_ghosts();
    return t;
}

}  // namespace avalanche
