#pragma once
// The DEM frame's per-cell coefficients (dem_frame.hpp) as functions of the bed's slope
// (z_x, z_y) alone. dem_terrain stores them for every cell it makes; the solver's
// per-cell passes compute them from the stored slopes instead of reading them (the
// same expressions, so the same bits: 32-48 bytes less of the grid read per cell and
// pass, which those passes wait for; docs/performance.md, "The DEM frame's
// coefficients from the slopes").
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
