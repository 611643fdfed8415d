#pragma once
// The speed cap of the stepper's energy budget (stepper.hpp): used by the update
// (update_rows.cpp), the thin-layer rule (stepper.cpp) and the kernels' reference tests.
#include <cmath>

namespace avalanche {

// Scales (u, v) so that the true speed^2 (speed2) does not exceed cap2; a cell
// with cap2 <= 0 lies above everything the material can reach and stops.
inline void cap_speed(double& u, double& v, double speed2, double cap2) {
    if (speed2 <= cap2) return;
    if (cap2 <= 0.0) {
        u = v = 0.0;
        return;
    }
    const double scale = std::sqrt(cap2 / speed2);
    u *= scale;
    v *= scale;
}

// cap_speed with selections instead of branches, for the vectorised row kernels: the
// same (u, v), the quotient and root computed for every cell and used where the cap acts.
[[gnu::always_inline]] inline void cap_speed_selected(double& u, double& v, double speed2,
                                                      double cap2) {
    const double scale = std::sqrt(cap2 / speed2);
    const bool over = !(speed2 <= cap2);
    u = over ? (cap2 <= 0.0 ? 0.0 : u * scale) : u;
    v = over ? (cap2 <= 0.0 ? 0.0 : v * scale) : v;
}

}  // namespace avalanche
