#include "avalanche/physics/chute.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "avalanche/core/error.hpp"

namespace avalanche {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
}

double ChuteGeometry::inclination(double x) const {
    const double z0 = slope_deg * kDeg;
    if (!has_transition()) return z0;
    const double z1 = runout_slope_deg * kDeg;
    const double a = *transition_start, b = *transition_end;
    if (x <= a) return z0;
    if (x >= b) return z1;
    return z0 + (z1 - z0) * (x - a) / (b - a);
}

double ChuteGeometry::curvature(double x) const {
    if (!has_transition()) return 0.0;
    const double a = *transition_start, b = *transition_end;
    if (x <= a || x >= b) return 0.0;
    return (slope_deg - runout_slope_deg) * kDeg / (b - a);
}

namespace {
// Integral of f(zeta(s)) ds from 0 to x for f = sin or cos, exact for the
// piecewise-linear zeta: on the plane and runout zeta is constant; in the
// transition d(zeta) = -kappa ds.
template <class F, class G>
double integrate(const ChuteGeometry& c, double x, F f, G antiderivative) {
    if (!c.has_transition()) return f(c.inclination(0.0)) * x;
    const double a = *c.transition_start, b = *c.transition_end;
    const double z0 = c.slope_deg * kDeg, z1 = c.runout_slope_deg * kDeg;
    double sum = f(z0) * std::min(x, a);
    if (x > a) {
        const double xe = std::min(x, b);
        const double ze = c.inclination(xe);
        const double dzds = (z1 - z0) / (b - a);
        sum += (antiderivative(ze) - antiderivative(z0)) / dzds;
    }
    if (x > b) sum += f(z1) * (x - b);
    return sum;
}
}  // namespace

double ChuteGeometry::elevation(double x) const {
    const auto drop = [&](double xx) {
        return integrate(*this, xx, [](double z) { return std::sin(z); },
                         [](double z) { return -std::cos(z); });
    };
    return drop(length) - drop(x);
}

double ChuteGeometry::horizontal_distance(double x) const {
    return integrate(*this, x, [](double z) { return std::cos(z); },
                     [](double z) { return std::sin(z); });
}

void validate(const ChuteGeometry& c) {
    if (!std::isfinite(c.slope_deg) || c.slope_deg < 0.0 || c.slope_deg >= 90.0)
        throw ConfigError("terrain.slope_deg", "expected an inclination in [0, 90) degrees");
    if (!std::isfinite(c.runout_slope_deg) || c.runout_slope_deg <= -90.0 || c.runout_slope_deg >= 90.0)
        throw ConfigError("terrain.runout_slope_deg", "expected an inclination in (-90, 90) degrees");
    if (!std::isfinite(c.length) || c.length <= 0.0)
        throw ConfigError("terrain.length", "expected a positive length in metres");
    if (!std::isfinite(c.width) || c.width <= 0.0)
        throw ConfigError("terrain.width", "expected a positive width in metres");
    if (c.transition_start.has_value() != c.transition_end.has_value())
        throw ConfigError("terrain.transition", "expected two values [start, end] in metres");
    if (c.has_transition()) {
        const double a = *c.transition_start, b = *c.transition_end;
        if (!(a >= 0.0 && b > a && b <= c.length))
            throw ConfigError("terrain.transition",
                              "expected 0 <= start < end <= length, got [" + std::to_string(a) + ", " +
                                  std::to_string(b) + "]");
    }
}

Grid chute_grid(const ChuteGeometry& c, double cell_size) {
    if (!std::isfinite(cell_size) || cell_size <= 0.0)
        throw ConfigError("numerics.cell_size", "expected a positive cell size in metres");
    Grid g;
    g.nx = static_cast<int>(std::lround(c.length / cell_size));
    g.ny = static_cast<int>(std::lround(c.width / cell_size));
    if (g.nx < 1 || g.ny < 1 || std::abs(g.nx * cell_size - c.length) > 1e-9 * c.length ||
        std::abs(g.ny * cell_size - c.width) > 1e-9 * c.width)
        throw ConfigError("numerics.cell_size", "expected a cell size that divides terrain.length (" +
                                                    std::to_string(c.length) + " m) and terrain.width (" +
                                                    std::to_string(c.width) + " m)");
    g.dx = g.dy = cell_size;
    return g;
}

TerrainFields chute_terrain(const ChuteGeometry& c, const Grid& grid, double gravity) {
    // The chute varies only down the slope: one row per field (Field2D::same_in_every_row);
    // ay, the cross curvatures cxy, cyy stay 0 and normal_thickness 1.
    TerrainFields t;
    t.frame = Frame::chute;
    t.allocate_same_in_every_row(grid, c.has_transition());
    double* ax = t.ax.every_row();
    double* px = t.px.every_row();
    double* py = t.py.every_row();
    double* gn = t.gn.every_row();
    double* z = t.elevation.every_row();
    double* cxx = t.has_curvature ? t.cxx.every_row() : nullptr;
    for (int i = 0; i < grid.nx; ++i) {
        const double x = grid.x_center(i);
        const double zeta = c.inclination(x);
        ax[i] = gravity * std::sin(zeta);
        px[i] = py[i] = gn[i] = gravity * std::cos(zeta);
        z[i] = c.elevation(x);
        if (cxx != nullptr) cxx[i] = c.curvature(x);
    }
    t.extend_to_ghosts();
    return t;
}

}  // namespace avalanche
