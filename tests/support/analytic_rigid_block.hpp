#pragma once
// Rigid-block limit of the Savage-Hutter equations (MODEL.md section 4): integrating
// the momentum balance over the whole mass, the pressure fluxes cancel (they are
// internal forces), so while every material point moves downslope on a plane of
// constant inclination theta the centroid obeys
//   x_c'' = g (sin(theta) - cos(theta) tan(delta)),
// whatever the shape and k (Savage & Hutter 1989, J. Fluid Mech. 199:177, sec. 5).
#include <cmath>

namespace avalanche::analytic {

[[nodiscard]] inline double rigid_block_acceleration(double theta_rad, double delta_rad,
                                                     double gravity) {
    return gravity * (std::sin(theta_rad) - std::cos(theta_rad) * std::tan(delta_rad));
}

// Centroid position at t from x0 and initial velocity u0.
[[nodiscard]] inline double rigid_block_centroid(double x0, double u0, double accel, double t) {
    return x0 + u0 * t + 0.5 * accel * t * t;
}

}  // namespace avalanche::analytic
