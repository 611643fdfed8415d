#include "extreme_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/earth_pressure.hpp"
#include "avalanche/physics/release.hpp"

namespace avalanche::extremes {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kGravity = 9.81;
constexpr double kCliff = 100.0;  // m between neighbouring cells at a cliff

template <class F>
std::vector<double> sample(const Grid& g, F z_of) {
    std::vector<double> z(g.cells());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) z[static_cast<std::size_t>(j) * g.nx + i] = z_of(i, j);
    return z;
}

// Cells scale with the release so that a 1 cm and a 200 m release are both
// resolved by a few cells (and the runs stay short): dx = max(1 m, h0 / 2).
double cell_for(double h0) { return std::max(1.0, 0.5 * h0); }

// Sets hu = h u0 where the release is (the moving releases).
void set_velocity(State& s, const Grid& g, double u0, double x_lo, double x_hi) {
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            if (g.x_center(i) >= x_lo && g.x_center(i) <= x_hi) s.hu(i, j) = s.h(i, j) * u0;
}

// Run time: long enough for the flow to cross the domain once at the speed it can
// reach, so fronts meet edges, cliffs and each other.
double crossing_time(double length, double slope_deg, double h0, double u0) {
    const double v = std::sqrt(kGravity * (length * std::sin(slope_deg * kDeg) + h0)) + u0;
    return 1.5 * length / v;
}

void build(Scene& s, const Case& c) {
    const double th = c.slope_deg * kDeg;
    switch (c.kind) {
        case Kind::plane_dem:
        case Kind::outflow:
        case Kind::single_cell: {
            const double dx = c.kind == Kind::single_cell ? 1.0 : cell_for(c.h0);
            s.grid = Grid{c.n, c.kind == Kind::single_cell ? c.n : c.n / 2, dx, dx, 0.0, 0.0};
            const double x_max = s.grid.x_max();
            s.terrain = dem_terrain(
                s.grid,
                sample(s.grid,
                       [&](int i, int) { return (x_max - s.grid.x_center(i)) * std::tan(th); }),
                kGravity);
            const double len = s.grid.x_max(), wid = s.grid.y_max();
            Field2D release(s.grid.nx, s.grid.ny, kGhostLayers, 0.0);
            if (c.kind == Kind::single_cell) {
                release(s.grid.nx / 2, s.grid.ny / 2) = c.h0;
            } else {
                const double xc = c.kind == Kind::outflow ? 0.85 * len : 0.3 * len;
                release =
                    rasterize_release(ParaboloidRelease{{xc, 0.5 * wid}, 0.2 * wid, c.h0}, s.grid);
            }
            s.initial = state_at_rest(s.grid, release, s.terrain);
            s.numerics.t_end = crossing_time(len, c.slope_deg, c.h0, 0.0);
            break;
        }
        case Kind::plane_chute: {
            ChuteGeometry geo;
            const double dx = cell_for(c.h0);
            geo.slope_deg = c.slope_deg;
            geo.length = c.n * dx;
            geo.width = (c.n / 2) * dx;
            s.grid = chute_grid(geo, dx);
            s.terrain = chute_terrain(geo, s.grid, kGravity);
            s.initial = state_at_rest(
                s.grid,
                rasterize_release(
                    ParaboloidRelease{{0.3 * geo.length, 0.5 * geo.width}, 0.2 * geo.width, c.h0},
                    s.grid),
                s.terrain);
            s.numerics.t_end = crossing_time(geo.length, c.slope_deg, c.h0, 0.0);
            break;
        }
        case Kind::cliff_staircase: {
            // Treads of 3 cells (30 m) falling 100 m each toward -x, a 60 m plateau on top;
            // the release on the plateau moves toward the first edge at u0.
            s.grid = Grid{c.n, 6, 10.0, 10.0, 0.0, 0.0};
            const int plateau = c.n - 6;
            s.terrain = dem_terrain(
                s.grid,
                sample(s.grid,
                       [&](int i, int) { return kCliff * std::floor(std::min(i, plateau) / 3.0); }),
                kGravity);
            const double x0 = plateau * 10.0;
            s.initial = state_at_rest(
                s.grid,
                rasterize_release(BoxRelease{{x0 + 10.0, x0 + 50.0}, {10.0, 50.0}, c.h0}, s.grid),
                s.terrain);
            set_velocity(s.initial, s.grid, -c.u0, x0, s.grid.x_max());
            s.numerics.t_end = 20.0;
            break;
        }
        case Kind::cliff_up: {
            // A flat floor (z = 0) ending in a 100 m wall between two neighbouring cells.
            s.grid = Grid{c.n, 6, 10.0, 10.0, 0.0, 0.0};
            const int wall = 2 * c.n / 3;
            s.terrain = dem_terrain(
                s.grid, sample(s.grid, [&](int i, int) { return i >= wall ? kCliff : 0.0; }),
                kGravity);
            s.initial = state_at_rest(
                s.grid, rasterize_release(BoxRelease{{20.0, 80.0}, {10.0, 50.0}, c.h0}, s.grid),
                s.terrain);
            set_velocity(s.initial, s.grid, c.u0, 0.0, 100.0);
            s.numerics.t_end = 10.0;
            break;
        }
        case Kind::collision_flat:
        case Kind::collision_valley: {
            const double dx = cell_for(c.h0);
            s.grid = Grid{c.n, 6, dx, dx, 0.0, 0.0};
            const double len = s.grid.x_max(), wid = s.grid.y_max();
            const bool valley = c.kind == Kind::collision_valley;
            s.terrain = dem_terrain(
                s.grid,
                sample(s.grid,
                       [&](int i, int) {
                           return valley ? std::abs(s.grid.x_center(i) - 0.5 * len) * std::tan(th)
                                         : 0.0;
                       }),
                kGravity);
            const double a = valley ? 0.05 : 0.1, b = valley ? 0.25 : 0.4;
            Field2D h = rasterize_release(BoxRelease{{a * len, b * len}, {0.0, wid}, c.h0}, s.grid);
            const Field2D h2 = rasterize_release(
                BoxRelease{{(1 - b) * len, (1 - a) * len}, {0.0, wid}, c.h0}, s.grid);
            for (std::size_t k = 0; k < h.raw().size(); ++k) h.raw()[k] += h2.raw()[k];
            s.initial = state_at_rest(s.grid, h, s.terrain);
            set_velocity(s.initial, s.grid, c.u0, 0.0, 0.5 * len);
            set_velocity(s.initial, s.grid, -c.u0, 0.5 * len, len);
            s.numerics.t_end = 2.0 * crossing_time(len, valley ? c.slope_deg : 0.0, c.h0, c.u0);
            break;
        }
    }
}

}  // namespace

Scene make_scene(const Case& c) {
    Scene s;
    s.material.phi_deg = c.phi_deg;
    s.material.delta_deg = c.delta_deg;
    s.material.earth_pressure = c.earth_pressure;
    s.numerics.scheme = c.scheme;
    s.numerics.cfl = c.cfl;
    s.numerics.splitting = c.splitting;
    s.numerics.rest_faces = c.rest_faces;
    s.numerics.h_min = c.h_min;
    build(s, c);
    s.numerics.output_interval = s.numerics.t_end;
    measure_release(s);
    return s;
}

void measure_release(Scene& s) {
    // Drop: highest release surface above the lowest bed. The surface height uses
    // h g / g_n (exact vertical extent in the chute frame, an over-estimate in the DEM
    // frame, where h is already vertical): the bound stays an upper bound.
    double top = -1e300, bottom = 1e300;
    for (int j = 0; j < s.grid.ny; ++j)
        for (int i = 0; i < s.grid.nx; ++i) {
            const double z = s.terrain.elevation(i, j);
            bottom = std::min(bottom, z);
            const double h = s.initial.h(i, j);
            if (h <= 0.0) continue;
            top = std::max(top, z + h * kGravity / s.terrain.coefficients(i, j).gn);
            s.h0 = std::max(s.h0, h * s.terrain.normal_thickness(i, j));
            s.u0 = std::max(s.u0, true_speed(s, s.initial, i, j));
        }
    s.drop = std::max(0.0, top - bottom);
}

double speed_bound(const Scene& s) {
    const EarthPressureCoefficients k = earth_pressure_coefficients(s.material);
    const double k_max = std::max({k.kx_active, k.kx_passive, k.ky_given_kx_active_active,
                                   k.ky_given_kx_active_passive, k.ky_given_kx_passive_active,
                                   k.ky_given_kx_passive_passive});
    const double g = s.numerics.gravity;
    return std::sqrt(s.u0 * s.u0 + 2.0 * g * s.drop) + 2.0 * std::sqrt(k_max * g * s.h0);
}

double true_speed(const Scene& s, const State& state, int i, int j) {
    const double h = state.h(i, j);
    if (h <= 0.0) return 0.0;
    const double u = state.hu(i, j) / h, v = state.hv(i, j) / h;
    double w = 0.0;
    if (s.terrain.has_metric) w = s.terrain.sx(i, j) * u + s.terrain.sy(i, j) * v;
    return std::sqrt(u * u + v * v + w * w);
}

}  // namespace avalanche::extremes
