#pragma once
// TVD flux limiters psi(r) in the WAF form of Toro (2009), section 14.3:
// the WAF weight of a wave with Courant number c is A = 1 - (1 - |c|) psi(r),
// so psi = 0 gives the Godunov upwind flux and psi = 1 the Lax-Wendroff one.
#include <algorithm>
#include <cmath>

#include "avalanche/numerics/parameters.hpp"

namespace avalanche {

[[nodiscard]] inline double limiter_psi(Limiter l, double r) noexcept {
    if (r <= 0.0) return 0.0;
    switch (l) {
        case Limiter::superbee: return std::max(std::min(2.0 * r, 1.0), std::min(r, 2.0));
        case Limiter::van_leer: return 2.0 * r / (1.0 + r);
        case Limiter::van_albada: return r * (1.0 + r) / (1.0 + r * r);
        case Limiter::minmod: return std::min(r, 1.0);
    }
    return 0.0;
}

// Ratio of the upwind jump to the local jump, r = d_upwind / d_local, with the
// flat and extremum cases made explicit: both jumps zero -> r = 1 (smooth, keep
// second order); local jump zero only -> r = 0 (extremum: upwind).
[[nodiscard]] inline double jump_ratio(double d_upwind, double d_local, double tiny) noexcept {
    if (std::abs(d_local) <= tiny) return std::abs(d_upwind) <= tiny ? 1.0 : 0.0;
    return d_upwind / d_local;
}

// limiter_psi(l, jump_ratio(d_upwind, d_local, tiny)) from the two jumps. Van Leer's
// 2r / (1 + r) is taken as 2 d_upwind / (d_local + d_upwind): one division instead of
// two (the same value up to round-off, and no inf / inf where r overflows); the
// other limiters go through r.
[[nodiscard]] inline double limiter_psi_of_jumps(Limiter l, double d_upwind, double d_local,
                                                 double tiny) noexcept {
    if (l != Limiter::van_leer) return limiter_psi(l, jump_ratio(d_upwind, d_local, tiny));
    if (std::abs(d_local) <= tiny) return std::abs(d_upwind) <= tiny ? 1.0 : 0.0;  // psi(1), psi(0)
    const bool positive = (d_upwind > 0.0 && d_local > 0.0) || (d_upwind < 0.0 && d_local < 0.0);
    return positive ? 2.0 * d_upwind / (d_local + d_upwind) : 0.0;
}

}  // namespace avalanche
