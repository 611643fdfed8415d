#pragma once
// Space-varying coefficients of the computational frame, precomputed once per
// scene (STYLE.md convention 4, Clawpack's aux arrays) and passed to kernels.
//
// Both frames reduce the model to one form (docs/theory.md):
//   dU/dt + dF/dx + dG/dy = S,
//   F = (hu, hu^2 + 1/2 k_x p_x h^2, huv),  G = (hv, huv, hv^2 + 1/2 k_y p_y h^2),
//   S = h (0, a_x, a_y) - friction,
//   friction: magnitude tan(delta) N against the true (along-surface) velocity,
//   N = g_n + c_xx u^2 + 2 c_xy u v + c_yy v^2 (clamped >= 0),
//   true speed^2 = u^2 + v^2 + (s_x u + s_y v)^2.
// Chute frame: a_x = g sin(zeta) - g cos(zeta) dz_b/dx, p = g_n = g cos(zeta),
//   c_xx = -dzeta/dx, s = 0 (bed-fitted coordinates, h bed-normal).
// DEM frame: horizontal grid, h vertical thickness, (u, v) horizontal velocity;
//   a = -g grad z / (1 + |grad z|^2), p_x = g cos^2(theta) / (1 + z_x^2),
//   g_n = g cos(theta), c = Hessian(z) / sqrt(1 + |grad z|^2), s = grad z.
#include <cstddef>

#include "avalanche/core/field.hpp"
#include "avalanche/core/grid.hpp"

namespace avalanche {

enum class Frame { chute, dem };

struct TerrainFields {
    Frame frame = Frame::chute;
    Field2D ax, ay;           // non-friction source acceleration (m/s^2)
    Field2D px, py;           // pressure coefficient without k, "g_z" (m/s^2)
    Field2D gn;               // bed-normal gravity for the friction load (m/s^2)
    Field2D cxx, cxy, cyy;    // curvature for the centripetal load (1/m); empty if none
    Field2D sx, sy;           // surface gradient for the true speed; empty in bed-fitted frames
    Field2D normal_thickness; // factor from the state's h to bed-normal thickness
    Field2D elevation;        // bed elevation (m); chute: height above the runout. Reports and the
                              // solver's energy cap use it: it must be the height whose gravity
                              // potential g z the accelerations ax, ay derive from.
    bool has_curvature = false;
    bool has_metric = false;

    // Allocates every field for the grid (curvature and metric only if asked).
    void allocate(const Grid& g, bool curvature, bool metric);
    // Fills ghost cells by zero-gradient extension of every allocated field.
    void extend_to_ghosts();
};

}  // namespace avalanche
