#include "random_scenes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <vector>

#include "avalanche/physics/dem_frame.hpp"
#include "avalanche/physics/release.hpp"

namespace avalanche::extremes {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kGravity = 9.81;
constexpr double kCliff = 100.0;  // m, the matrix's cliff between neighbouring cells
// In the order of enum Limiter (parameters.hpp), for the scene's description.
constexpr const char* kLimiterNames[] = {"superbee", "van_leer", "van_albada", "minmod"};

// Draws from the engine's integers only: std::uniform_real_distribution's algorithm
// is the library's, so its values could differ between standard libraries.
class Draw {
  public:
    explicit Draw(std::uint64_t seed) : rng_(seed) {}
    double uniform(double lo, double hi) {  // [lo, hi)
        return lo + (hi - lo) * static_cast<double>(rng_() >> 11) * 0x1.0p-53;
    }
    double log_uniform(double lo, double hi) {
        return std::exp(uniform(std::log(lo), std::log(hi)));
    }
    int integer(int lo, int hi) {  // [lo, hi]
        return lo + static_cast<int>(rng_() % static_cast<std::uint64_t>(hi - lo + 1));
    }
    bool chance(double p) { return uniform(0.0, 1.0) < p; }

  private:
    std::mt19937_64 rng_;
};

// The terrain: a plane falling at `slope` toward `azimuth`, roughened by bumps of up
// to `roughness` cell heights, with cliffs: steps of 100 m across whole rows or
// columns, single cells raised into towers or sunk into pits of 100 m, or none.
std::vector<double> rough_dem(const Grid& g, Draw& d, std::ostringstream& what) {
    const double slope = d.uniform(0.0, 80.0), azimuth = d.uniform(0.0, 360.0);
    const double roughness = d.chance(0.3) ? 0.0 : d.uniform(0.0, 2.0);
    what << "slope " << slope << " deg toward " << azimuth << " deg, roughness " << roughness;
    const double gx = std::tan(slope * kDeg) * std::cos(azimuth * kDeg);
    const double gy = std::tan(slope * kDeg) * std::sin(azimuth * kDeg);
    std::vector<double> z(g.cells());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            z[static_cast<std::size_t>(j) * g.nx + i] = -(gx * g.x_center(i) + gy * g.y_center(j)) +
                                                        roughness * g.dx * d.uniform(-1.0, 1.0);
    const int cliffs = d.integer(0, 3);
    for (int k = 0; k < cliffs; ++k) {
        const int kind = d.integer(0, 2);
        const double sign = d.chance(0.5) ? 1.0 : -1.0;
        if (kind == 0) {  // a step across the grid at column i0 (x) or row j0 (y)
            const bool along_x = d.chance(0.5);
            const int at = along_x ? d.integer(1, g.nx - 1) : d.integer(1, g.ny - 1);
            what << "; step " << sign * kCliff << " m at " << (along_x ? "i = " : "j = ") << at;
            for (int j = 0; j < g.ny; ++j)
                for (int i = 0; i < g.nx; ++i)
                    if ((along_x ? i : j) >= at)
                        z[static_cast<std::size_t>(j) * g.nx + i] += sign * kCliff;
        } else {  // towers (kind 1) or pits (kind 2) of single cells
            const int cells = d.integer(1, std::max(1, static_cast<int>(g.cells() / 10)));
            const double dz = kind == 1 ? kCliff : -kCliff;
            what << "; " << cells << (kind == 1 ? " towers" : " pits");
            for (int c = 0; c < cells; ++c)
                z[static_cast<std::size_t>(d.integer(0, g.ny - 1)) * g.nx +
                  d.integer(0, g.nx - 1)] += dz;
        }
    }
    return z;
}

// One to three releases: paraboloids or boxes of up to h0, each at rest or moving
// in its own direction at up to 50 m/s.
void add_releases(Scene& s, Draw& d, double h0, std::ostringstream& what) {
    const Grid& g = s.grid;
    const int count = d.integer(1, 3);
    Field2D total(g.nx, g.ny, kGhostLayers, 0.0);
    std::vector<std::array<double, 2>> velocity(g.cells(), {0.0, 0.0});
    for (int r = 0; r < count; ++r) {
        const double thickness = h0 * (r == 0 ? 1.0 : d.uniform(0.05, 1.0));
        const double xc = d.uniform(0.0, g.x_max()), yc = d.uniform(0.0, g.y_max());
        const double size = std::max(g.dx, d.uniform(0.05, 0.4) * std::max(g.x_max(), g.y_max()));
        Field2D h = d.chance(0.5)
                        ? rasterize_release(ParaboloidRelease{{xc, yc}, size, thickness}, g)
                        : rasterize_release(BoxRelease{{xc - size / 2, xc + size / 2},
                                                       {yc - size / 2, yc + size / 2},
                                                       thickness},
                                            g);
        const double speed = d.chance(0.5) ? 0.0 : d.uniform(0.0, 50.0);
        const double direction = d.uniform(0.0, 360.0);
        what << "; release " << thickness << " m at (" << xc << ", " << yc << ") size " << size
             << " moving " << speed << " m/s toward " << direction << " deg";
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i)
                if (h(i, j) > 0.0) {
                    total(i, j) += h(i, j);
                    velocity[static_cast<std::size_t>(j) * g.nx + i] = {
                        speed * std::cos(direction * kDeg), speed * std::sin(direction * kDeg)};
                }
    }
    // A release that misses every cell centre still puts one cell of h0 on the grid.
    bool any = false;
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) any = any || total(i, j) > 0.0;
    if (!any) total(g.nx / 2, g.ny / 2) = h0;
    s.initial = state_at_rest(g, total, s.terrain);
    // Moving releases: the drawn speed is the true (along-surface) one. The state holds
    // the horizontal velocity (u, v) of the DEM frame, whose true speed is
    // |(u, v)| sqrt(1 + (s . e)^2) along the unit direction e: on the side of a 100 m
    // tower of 1 m cells a horizontal 50 m/s would be 2500 m/s along the surface.
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const auto& v = velocity[static_cast<std::size_t>(j) * g.nx + i];
            const double speed = std::hypot(v[0], v[1]);
            double scale = 1.0;
            if (speed > 0.0) {
                const double rise = (s.terrain.sx(i, j) * v[0] + s.terrain.sy(i, j) * v[1]) / speed;
                scale = 1.0 / std::sqrt(1.0 + rise * rise);
            }
            s.initial.hu(i, j) = s.initial.h(i, j) * v[0] * scale;
            s.initial.hv(i, j) = s.initial.h(i, j) * v[1] * scale;
        }
}

}  // namespace

RandomScene random_scene(std::uint64_t seed) {
    Draw d(seed);
    RandomScene out;
    Scene& s = out.scene;
    std::ostringstream what;
    what.precision(4);
    what << "seed " << seed << ": ";

    MaterialParams& m = s.material;
    m.delta_deg = d.chance(0.1) ? 0.0 : d.uniform(0.0, 45.0);
    m.phi_deg = std::max(1.0, d.uniform(m.delta_deg, 50.0));
    m.earth_pressure =
        d.chance(0.5) ? EarthPressureModel::savage_hutter : EarthPressureModel::isotropic;
    NumericsParams& n = s.numerics;
    n.scheme = d.chance(0.5) ? Scheme::waf : Scheme::godunov;
    n.limiter = static_cast<Limiter>(d.integer(0, 3));
    n.splitting = d.chance(0.5) ? Splitting::lsl : Splitting::sls;
    n.cfl = d.uniform(0.05, 0.5);
    n.h_min = d.chance(0.3) ? 0.0 : d.log_uniform(1e-8, 1e-2);
    n.rest_faces = d.chance(0.3);
    n.boundary = d.chance(0.7) ? Boundary::open : Boundary::wall;
    n.source_substeps = d.chance(0.8) ? 1 : d.integer(2, 4);
    n.active_margin = d.chance(0.8) ? 4 : d.integer(3, 8);
    const double h0 = d.log_uniform(0.01, 200.0);
    // Cells of 1 m up to a quarter of the release thickness times 1-4, so that deep
    // releases span a few cells and thin ones many (as the matrix's cell_for).
    const double dx = std::max(1.0, 0.25 * h0) * d.uniform(1.0, 4.0);
    // One grid in five has over 64 rows, so that the advection cuts its box into
    // several bands (Stepper::make_bands) between the releases.
    const int nx = d.integer(3, 32), ny = d.chance(0.2) ? d.integer(65, 160) : d.integer(3, 24);
    s.grid = Grid{nx, ny, dx, dx, 0.0, 0.0};
    what << m.delta_deg << "/" << m.phi_deg << " deg "
         << (m.earth_pressure == EarthPressureModel::savage_hutter ? "savage-hutter" : "isotropic")
         << ", " << (n.scheme == Scheme::waf ? "waf" : "godunov") << " "
         << kLimiterNames[static_cast<int>(n.limiter)] << " "
         << (n.splitting == Splitting::lsl ? "lsl" : "sls") << " C " << n.cfl << ", h_min "
         << n.h_min << ", rest_faces " << n.rest_faces << ", "
         << (n.boundary == Boundary::open ? "open" : "wall") << " edges, " << n.source_substeps
         << " source substeps, margin " << n.active_margin << "; grid " << nx << " x " << ny
         << " of " << dx << " m, h0 " << h0 << " m; ";
    s.terrain = dem_terrain(s.grid, rough_dem(s.grid, d, what), kGravity);
    add_releases(s, d, h0, what);
    measure_release(s);
    // Long enough to cross the grid three times at a third of the free-fall bound:
    // fronts meet edges, cliffs and each other, and slow flows come to rest.
    const double length = std::max(s.grid.x_max(), s.grid.y_max());
    n.t_end = 9.0 * length / std::max(1.0, speed_bound(s));
    n.output_interval = n.t_end;
    out.description = what.str();
    return out;
}

namespace {

// A scene with s's material, numerics and bounds on grid g, its terrain made at once
// from z and its initial state empty (the caller fills it). Not a copy of s with parts
// replaced: copying a terrain made on demand makes all of it (TerrainFields' copy),
// and s's run would then not be on demand.
Scene rebuilt(const Scene& s, const Grid& g, const std::vector<double>& z) {
    Scene r;
    r.grid = g;
    r.material = s.material;
    r.numerics = s.numerics;
    r.drop = s.drop;
    r.u0 = s.u0;
    r.h0 = s.h0;
    r.terrain = dem_terrain(g, z, kGravity);
    r.terrain.ensure_everywhere();
    r.initial = State(g);
    return r;
}

}  // namespace

Scene mirrored(const Scene& s, Axis axis) {
    const Grid& g = s.grid;
    const auto mi = [&](int i) { return axis == Axis::x ? g.nx - 1 - i : i; };
    const auto mj = [&](int j) { return axis == Axis::y ? g.ny - 1 - j : j; };
    std::vector<double> z(g.cells());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            z[static_cast<std::size_t>(mj(j)) * g.nx + mi(i)] = s.terrain.elevation(i, j);
    Scene m = rebuilt(s, g, z);
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            m.initial.h(mi(i), mj(j)) = s.initial.h(i, j);
            m.initial.hu(mi(i), mj(j)) = axis == Axis::x ? -s.initial.hu(i, j) : s.initial.hu(i, j);
            m.initial.hv(mi(i), mj(j)) = axis == Axis::y ? -s.initial.hv(i, j) : s.initial.hv(i, j);
        }
    return m;
}

Scene cropped(const Scene& s, const ActiveBox& box) {
    const Grid& g = s.grid;
    const Grid cut{box.i1 - box.i0,      box.j1 - box.j0,     g.dx, g.dy,
                   g.x0 + box.i0 * g.dx, g.y0 + box.j0 * g.dy};
    std::vector<double> z(cut.cells());
    for (int j = 0; j < cut.ny; ++j)
        for (int i = 0; i < cut.nx; ++i)
            z[static_cast<std::size_t>(j) * cut.nx + i] =
                s.terrain.elevation(i + box.i0, j + box.j0);
    Scene c = rebuilt(s, cut, z);
    for (int j = 0; j < cut.ny; ++j)
        for (int i = 0; i < cut.nx; ++i) {
            c.initial.h(i, j) = s.initial.h(i + box.i0, j + box.j0);
            c.initial.hu(i, j) = s.initial.hu(i + box.i0, j + box.j0);
            c.initial.hv(i, j) = s.initial.hv(i + box.i0, j + box.j0);
        }
    return c;
}

bool mirror_images(const State& a, const State& b, Axis axis) {
    const int nx = a.h.nx(), ny = a.h.ny();
    // Equal values, not equal bits: the mirror of a momentum of +0 may be -0 (a product
    // with a reversed velocity), which is the same state.
    const auto same = [](double x, double y) { return x == y; };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int ii = axis == Axis::x ? nx - 1 - i : i, jj = axis == Axis::y ? ny - 1 - j : j;
            const double hu = axis == Axis::x ? -b.hu(ii, jj) : b.hu(ii, jj);
            const double hv = axis == Axis::y ? -b.hv(ii, jj) : b.hv(ii, jj);
            if (!same(a.h(i, j), b.h(ii, jj)) || !same(a.hu(i, j), hu) || !same(a.hv(i, j), hv))
                return false;
        }
    return true;
}

}  // namespace avalanche::extremes
