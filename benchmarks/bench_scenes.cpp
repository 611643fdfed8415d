#include "bench_scenes.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "avalanche/core/simulation.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"

namespace avalanche::bench {

namespace {
constexpr double kGravity = 9.81;
constexpr double kDeg = std::numbers::pi / 180.0;

// Elevations of a DEM grid from a function of the cell centre (solver orientation);
// adds the seconds it took to `seconds`.
template <class F>
std::vector<double> sample_dem(const Grid& g, F z_of, double& seconds) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<double> z(g.cells());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            z[static_cast<std::size_t>(j) * g.nx + i] = z_of(g.x_center(i), g.y_center(j));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return z;
}

// h_min as the tool chooses it (numerics.h_min = 0: relative to the deepest cell).
void finish(Scene& s) { s.h_min = effective_h_min(s.numerics, s.initial, s.terrain, s.released); }
}  // namespace

std::string to_string(Scheme s) { return s == Scheme::waf ? "waf" : "godunov"; }

Scene tilted_plane(int n, double cell_size, double slope_deg, double thickness, Scheme scheme) {
    Scene s;
    s.name = "a_tilted_plane";
    s.grid = Grid{n, n, cell_size, cell_size, 0.0, 0.0};
    const double tan_t = std::tan(slope_deg * kDeg);
    const double x_max = s.grid.x_max();
    s.terrain = dem_terrain(
        s.grid, sample_dem(s.grid, [&](double x, double) { return (x_max - x) * tan_t; }, s.dem_seconds),
        kGravity);
    s.material.phi_deg = 35.0;
    s.material.delta_deg = 20.0;
    s.numerics.scheme = scheme;
    s.numerics.t_end = 1e6;  // the run is cut by a step count
    s.numerics.output_interval = 1e6;
    s.initial = state_at_rest(s.grid, Field2D(n, n, kGhostLayers, thickness), s.terrain, &s.released);
    finish(s);
    return s;
}

Scene paper_chute(double cell_size, Scheme scheme) {
    Scene s;
    s.name = "b_paper_chute";
    ChuteGeometry c;  // 45 deg, 60 x 40 m
    c.transition_start = 25.0;
    c.transition_end = 30.0;
    c.runout_slope_deg = 0.0;
    s.grid = chute_grid(c, cell_size);
    s.terrain = chute_terrain(c, s.grid, kGravity);
    s.material.phi_deg = 35.0;
    s.material.delta_deg = 20.0;
    s.numerics.scheme = scheme;
    s.numerics.t_end = 60.0;
    s.numerics.output_interval = 60.0;
    const ReleaseShape cap = CapRelease{{7.5, 20.0}, 2.5};
    s.initial =
        state_at_rest(s.grid, rasterize_release(cap, s.grid), s.terrain, release_cells(cap, s.grid), &s.released);
    finish(s);
    return s;
}

double valley_elevation(double x, double y) {
    constexpr double a = 2e-4, w = 1500.0;  // cross-section: 450 m high, 31 deg at |x| = w
    const double d = std::abs(x);
    const double cross = d <= w ? a * d * d : a * w * w + 2.0 * a * w * (d - w);
    constexpr double length = 10000.0, b = 3000.0 / (length * length);
    double along = 0.0;
    if (y > length)
        along = b * length * length + 2.0 * b * length * (y - length);
    else if (y > 0.0)
        along = b * y * y;
    return cross + along;
}

Scene valley(int nx, int ny, double cell_size, double x0, double y0, const ValleyRelease& r,
             Scheme scheme, double t_end) {
    Scene s;
    s.name = "valley";
    s.grid = Grid{nx, ny, cell_size, cell_size, x0, y0};
    s.terrain = dem_terrain(s.grid, sample_dem(s.grid, valley_elevation, s.dem_seconds), kGravity);
    s.material.phi_deg = 25.0;
    s.material.delta_deg = 12.5;
    s.numerics.scheme = scheme;
    s.numerics.t_end = t_end;
    s.numerics.output_interval = t_end;
    // The release is placed in world coordinates (the grid's x0, y0 included), so a
    // crop and the full DEM hold the same release up to round-off.
    const ReleaseShape shape = ParaboloidRelease{{r.xc, r.yc}, r.radius, r.thickness};
    s.initial = state_at_rest(s.grid, rasterize_release(shape, s.grid), s.terrain, release_cells(shape, s.grid),
                              &s.released);
    finish(s);
    return s;
}

}  // namespace avalanche::bench
