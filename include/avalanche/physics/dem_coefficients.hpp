#pragma once
// The DEM frame's per-cell coefficients (dem_frame.hpp) as functions of the bed's slope
// (z_x, z_y) alone. dem_terrain stores the slopes and, of these, only the normal
// thickness (the products read it cell by cell); every reader of the others computes
// them from the stored slopes (TerrainFields::coefficients, the solver's row kernels):
// fewer bytes of the grid per cell and pass, which those passes wait for, and 40 bytes
// per cell less to keep (docs/performance.md, "The DEM frame's coefficients from the
// slopes", "The DEM frame stores its slopes").
#include <cmath>

namespace avalanche {

struct DemCoefficients {
    double ax, ay;            // -g grad z / s^2
    double px, py;            // g / (s^2 (1 + z_x^2)), g / (s^2 (1 + z_y^2))
    double gn;                // g / s, the load without curvature
    double normal_thickness;  // 1 / s
};

// Inline, so that a kernel's unused coefficients cost nothing.
[[nodiscard]] inline DemCoefficients dem_coefficients(double zx, double zy, double gravity) noexcept {
    const double s2 = 1.0 + zx * zx + zy * zy;
    const double s = std::sqrt(s2);
    return {-gravity * zx / s2,
            -gravity * zy / s2,
            gravity / (s2 * (1.0 + zx * zx)),
            gravity / (s2 * (1.0 + zy * zy)),
            gravity / s,
            1.0 / s};
}

}  // namespace avalanche
