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
    double gn_nt;             // g / s^2 = gn * normal_thickness, the load on a bed-normal depth
};

// Inline, so that a kernel's unused coefficients cost nothing.
//
// One division and one root for all of them: the reciprocal of s^2 (1 + z_x^2)
// (1 + z_y^2) gives p_x, p_y and 1 / s^2 as products, and 1 / s is the root of 1 / s^2.
// The row kernels compute these for every cell at every pass, and on processors whose
// divider is slow next to their multipliers (Zen 4: 3.3 G divisions and 1.8 G roots per
// second and core, 9.7 G multiplications) the advection's pressure stage waited for it.
// The quotients took six divisions and a root, of which the pressure stage used four
// and the root (docs/performance.md, "The DEM frame's coefficients with one division").
// Each value is within a few ulps of its quotient.
// Finite for slopes below 1e77 in magnitude (the product in the divisor overflows
// beyond): any terrain, whose void markers the DEM reader refuses.
[[nodiscard]] inline DemCoefficients dem_coefficients(double zx, double zy, double gravity) noexcept {
    const double a = 1.0 + zx * zx, b = 1.0 + zy * zy;
    const double s2 = a + zy * zy;
    const double ab = a * b;
    const double r = 1.0 / (s2 * ab);
    const double inv_s2 = ab * r;
    const double nt = std::sqrt(inv_s2);
    return {-gravity * zx * inv_s2,
            -gravity * zy * inv_s2,
            gravity * b * r,
            gravity * a * r,
            gravity * nt,
            nt,
            gravity * inv_s2};
}

}  // namespace avalanche
