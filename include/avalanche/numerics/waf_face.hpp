#pragma once
// The WAF-TVD flux of one face, in scalar form: the definition the stepper's
// vectorised row kernels (face_flux_rows.hpp) reproduce bitwise, and the reference
// their tests compare against. A face between cells L and R reads the four-cell
// stencil LL, L, R, RR (Wang & Li 2017 eq. 9; Toro 2009 section 14.3).
#include <algorithm>
#include <cmath>

#include "avalanche/numerics/limiters.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/numerics/riemann_hllc.hpp"

namespace avalanche {

namespace detail {
inline double velocity_or_zero(const Conserved& q, double h_dry) {
    return q.h >= h_dry && q.h > 0.0 ? q.qt / q.h : 0.0;
}
}  // namespace detail

// h_dry must be positive (then a face without a front has two wet sides).
[[nodiscard]] inline Conserved waf_face_flux(const Conserved& qll, const Conserved& ql,
                                             const Conserved& qr, const Conserved& qrr, double c_l,
                                             double c_r, double h_dry, double dt_dx,
                                             Limiter lim) noexcept {
    // A local jump counts as flat when it is below 1e-12 of the values it is the
    // difference of: relative, so that the decision does not depend on units or
    // on the frame (DEM and chute frames scale h and u by cos(theta)), and above
    // round-off, so that a jump of a few ulps does not swing psi from 0 to 2.
    constexpr double kFlat = 1e-12;
    // At a wet/dry front (a stencil cell thinner than h_min) the WAF weights
    // lose their meaning: use the first-order upwind flux there, as
    // thin-layer schemes do (Wang & Li 2017 section 2.2.3).
    const bool front = qll.h < h_dry || ql.h < h_dry || qr.h < h_dry || qrr.h < h_dry;
    if (front) return hllc_flux(ql, qr, c_l, c_r, h_dry);  // only the upwind region's flux
    const HllcFan fan = hllc_fan(ql, qr, c_l, c_r, h_dry);
    // Limiter ratios. The shear wave is limited on the jump of the
    // transverse velocity (Toro 2009 section 16.7). Each outer wave is
    // limited on its own strength: the jumps of (h, q_n) at this face and
    // at the upwind face are projected on the local eigenvectors of the
    // flux Jacobian, alpha_1 = ((u + a) dh - dq) / 2a and
    // alpha_3 = (dq - (u - a) dh) / 2a (LeVeque 2002 section 6.12).
    // A depth ratio alone let a face with equal depths but a velocity
    // jump take psi -> 2 (a downwind flux) and runs failed; the minimum of
    // the depth and momentum ratios was robust but first order on smooth
    // flow. The wave strengths are both robust and second order.
    const double h_bar = 0.5 * (ql.h + qr.h);
    const double u_bar = 0.5 * (fan.ul + fan.ur);  // both wet here: q_n / h
    const double a_bar = std::sqrt(0.5 * (c_l + c_r) * h_bar);
    // The limiter reads only the ratio of two strengths of a wave, so their common
    // factor 1 / 2a is left out: 2a alpha_1 and 2a alpha_3 (two divisions per wave
    // fewer; the same ratio up to round-off).
    const auto strength = [&](int wave, double dh, double dq) {
        return wave == 0 ? (u_bar + a_bar) * dh - dq : dq - (u_bar - a_bar) * dh;
    };
    // Strengths below 1e-12 of the depth count as flat (relative, so the
    // choice does not depend on units or frame): 2a alpha below 2a 1e-12 h_bar.
    const double tiny_alpha = kFlat * h_bar * (2.0 * a_bar);
    const double s_wave[3] = {fan.s_l, fan.s_star, fan.s_r};
    double psi[3];
    for (int m = 0; m < 3; ++m) {
        const bool from_left = s_wave[m] >= 0.0;
        if (m == 1) {
            // fan.vl, fan.vr are velocity(ql, hd), velocity(qr, hd), already divided.
            const double dv_loc = fan.vr - fan.vl;
            const double dv_up = from_left ? fan.vl - detail::velocity_or_zero(qll, h_dry)
                                           : detail::velocity_or_zero(qrr, h_dry) - fan.vr;
            const double tiny_v = kFlat * std::max(std::abs(fan.vl), std::abs(fan.vr));
            psi[m] = limiter_psi_of_jumps(lim, dv_up, dv_loc, tiny_v);
        } else {
            const double local = strength(m, qr.h - ql.h, qr.qn - ql.qn);
            const double upwind = from_left ? strength(m, ql.h - qll.h, ql.qn - qll.qn)
                                            : strength(m, qrr.h - qr.h, qrr.qn - qr.qn);
            psi[m] = limiter_psi_of_jumps(lim, upwind, local, tiny_alpha);
        }
    }
    return waf_flux(fan, dt_dx, psi);
}

}  // namespace avalanche
