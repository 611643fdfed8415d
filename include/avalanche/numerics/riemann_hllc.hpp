#pragma once
// HLLC approximate Riemann solver for the Savage–Hutter fluxes in one direction
// (Toro 2009, ch. 10 and 13; Wang & Li 2017 eq. 10). Pure functions of the face
// states and face coefficients: no members, no globals, no allocation
// (STYLE.md convention 1). The y-direction reuses them with (hu, hv) swapped.
//
// A face state holds (h, normal momentum, tangential momentum). The pressure
// coefficient c = k g_z of each side enters the physical flux
//   F(q; c) = (q_n, q_n^2/h + 1/2 c h^2, q_n q_t / h)
// and the celerity a = sqrt(c h). States with h < h_dry are treated as dry
// (thin-layer rule, Wang & Li 2017 section 2.2.3) and use the Riemann-invariant
// front speeds u -/+ 2a of the wet side.
#include <algorithm>
#include <cmath>

namespace avalanche {

struct Conserved {
    double h = 0.0;    // thickness
    double qn = 0.0;   // momentum normal to the face
    double qt = 0.0;   // momentum along the face
};

// The four HLLC fluxes F_L, F*_L, F*_R, F_R and the three wave speeds.
struct HllcFan {
    double s_l = 0.0, s_star = 0.0, s_r = 0.0;
    Conserved flux[4];
    double ul = 0.0, vl = 0.0, ur = 0.0, vr = 0.0;  // side velocities (0 on a dry side), for the WAF limiters
};

[[nodiscard]] inline Conserved physical_flux(double h, double u, double v, double c) noexcept {
    const double qn = h * u;
    return {qn, qn * u + 0.5 * c * h * h, qn * v};
}

// Wave speeds and fluxes of the HLLC fan. Davis (1988) speed estimates for two
// wet states; dry-front speeds when one side is dry.
[[nodiscard]] inline HllcFan hllc_fan(const Conserved& ql, const Conserved& qr, double c_l, double c_r,
                                      double h_dry) noexcept {
    HllcFan fan;
    const bool wet_l = ql.h >= h_dry && ql.h > 0.0;
    const bool wet_r = qr.h >= h_dry && qr.h > 0.0;
    if (!wet_l && !wet_r) return fan;  // all fluxes and speeds zero

    const double hl = wet_l ? ql.h : 0.0, hr = wet_r ? qr.h : 0.0;
    const double ul = wet_l ? ql.qn / hl : 0.0, vl = wet_l ? ql.qt / hl : 0.0;
    const double ur = wet_r ? qr.qn / hr : 0.0, vr = wet_r ? qr.qt / hr : 0.0;
    const double al = std::sqrt(c_l * hl), ar = std::sqrt(c_r * hr);
    fan.ul = ul;
    fan.vl = vl;
    fan.ur = ur;
    fan.vr = vr;

    fan.flux[0] = physical_flux(hl, ul, vl, c_l);
    fan.flux[3] = physical_flux(hr, ur, vr, c_r);

    // Star fluxes of the shallow-water HLLC (Toro 2001, section 10.3; Toro 2009
    // section 10.6): mass and normal momentum are the HLL flux on both sides of the
    // contact, so only the tangential momentum (a passive scalar) jumps across it:
    //   F*_K = (F_hll.h, F_hll.qn, F_hll.h v_K).
    const auto hll = [&](double s_l, double s_r, double h_l, double qn_l, double h_r, double qn_r) {
        const Conserved& fl = fan.flux[0];
        const Conserved& fr = fan.flux[3];
        const double inv = 1.0 / (s_r - s_l);
        return Conserved{(s_r * fl.h - s_l * fr.h + s_l * s_r * (h_r - h_l)) * inv,
                         (s_r * fl.qn - s_l * fr.qn + s_l * s_r * (qn_r - qn_l)) * inv, 0.0};
    };

    if (!wet_r) {  // right dry: rarefaction front at u_L + 2 a_L, s* = s_R
        fan.s_l = ul - al;
        fan.s_star = fan.s_r = ul + 2.0 * al;
        Conserved star = hll(fan.s_l, fan.s_r, hl, hl * ul, 0.0, 0.0);
        star.qt = star.h * vl;
        fan.flux[1] = fan.flux[2] = star;  // the jump to the dry state sits on the right wave
        return fan;
    }
    if (!wet_l) {  // left dry: front at u_R - 2 a_R, s* = s_L
        fan.s_l = fan.s_star = ur - 2.0 * ar;
        fan.s_r = ur + ar;
        Conserved star = hll(fan.s_l, fan.s_r, 0.0, 0.0, hr, hr * ur);
        star.qt = star.h * vr;
        fan.flux[1] = fan.flux[2] = star;  // the jump to the dry state sits on the left wave
        return fan;
    }
    fan.s_l = std::min(ul - al, ur - ar);
    fan.s_r = std::max(ul + al, ur + ar);
    // Denominator < 0 strictly for two wet states: h_R (u_R - s_R) <= -h_R a_R and
    // -h_L (u_L - s_L) <= -h_L a_L.
    fan.s_star = (fan.s_l * hr * (ur - fan.s_r) - fan.s_r * hl * (ul - fan.s_l)) /
                 (hr * (ur - fan.s_r) - hl * (ul - fan.s_l));
    const Conserved star = hll(fan.s_l, fan.s_r, hl, hl * ul, hr, hr * ur);
    fan.flux[1] = {star.h, star.qn, star.h * vl};
    fan.flux[2] = {star.h, star.qn, star.h * vr};
    return fan;
}

// First-order Godunov flux: the HLLC flux of the region that contains s = 0.
[[nodiscard]] inline Conserved hllc_flux(const HllcFan& fan) noexcept {
    if (fan.s_l >= 0.0) return fan.flux[0];
    if (fan.s_star >= 0.0) return fan.flux[1];
    if (fan.s_r >= 0.0) return fan.flux[2];
    return fan.flux[3];
}

// The same flux without building the whole fan: the speeds first, then only the
// flux of the region that contains s = 0 (in supercritical flow, the common case on
// a slope, that is one physical flux). Every value is computed by the same
// expressions as in hllc_fan, so the result is bitwise that of hllc_flux(hllc_fan(..))
// (tests/regression/test_kernel_equivalence.cpp).
[[nodiscard]] inline Conserved hllc_flux(const Conserved& ql, const Conserved& qr, double c_l, double c_r,
                                         double h_dry) noexcept {
    const bool wet_l = ql.h >= h_dry && ql.h > 0.0;
    const bool wet_r = qr.h >= h_dry && qr.h > 0.0;
    if (!wet_l && !wet_r) return {};
    const double hl = wet_l ? ql.h : 0.0, hr = wet_r ? qr.h : 0.0;
    const double ul = wet_l ? ql.qn / hl : 0.0, vl = wet_l ? ql.qt / hl : 0.0;
    const double ur = wet_r ? qr.qn / hr : 0.0, vr = wet_r ? qr.qt / hr : 0.0;
    const double al = std::sqrt(c_l * hl), ar = std::sqrt(c_r * hr);
    double s_l, s_star, s_r;
    if (!wet_r) {
        s_l = ul - al;
        s_star = s_r = ul + 2.0 * al;
    } else if (!wet_l) {
        s_l = s_star = ur - 2.0 * ar;
        s_r = ur + ar;
    } else {
        s_l = std::min(ul - al, ur - ar);
        s_r = std::max(ul + al, ur + ar);
        s_star = (s_l * hr * (ur - s_r) - s_r * hl * (ul - s_l)) / (hr * (ur - s_r) - hl * (ul - s_l));
    }
    if (s_l >= 0.0) return physical_flux(hl, ul, vl, c_l);
    if (s_star < 0.0 && s_r < 0.0) return physical_flux(hr, ur, vr, c_r);
    // Star region: the HLL mass and normal momentum fluxes (a dry side has h = q = 0
    // and a zero physical flux, as in hllc_fan), the tangential momentum upwind of
    // the contact. A dry left side has s_* = s_L < 0, so the left star state is
    // reached only with a wet left side (and the right one only with a wet right side).
    const Conserved fl = physical_flux(hl, ul, vl, c_l), fr = physical_flux(hr, ur, vr, c_r);
    const double inv = 1.0 / (s_r - s_l);
    const double fh = (s_r * fl.h - s_l * fr.h + s_l * s_r * (hr - hl)) * inv;
    const double fq = (s_r * fl.qn - s_l * fr.qn + s_l * s_r * (hr * ur - hl * ul)) * inv;
    return {fh, fq, fh * (s_star >= 0.0 ? vl : vr)};
}

// WAF flux (Toro 2009 eq. 14.52; Wang & Li 2017 eq. 9):
//   F = 1/2 (F_L + F_R) - 1/2 sum_m sign(c_m) A_m (F^(m) - F^(m-1)),
// with c_m = s_m dt/dx and the limited weights A_m = 1 - (1 - |c_m|) psi_m given by
// the caller through psi[3] (one limiter value per wave).
[[nodiscard]] inline Conserved waf_flux(const HllcFan& fan, double dt_over_dx, const double psi[3]) noexcept {
    const double s[3] = {fan.s_l, fan.s_star, fan.s_r};
    double w[3];
    for (int m = 0; m < 3; ++m) {
        const double c = std::clamp(s[m] * dt_over_dx, -1.0, 1.0);
        const double a = 1.0 - (1.0 - std::abs(c)) * psi[m];
        w[m] = c > 0.0 ? 0.5 * a : (c < 0.0 ? -0.5 * a : 0.0);  // sign(0) = 0
    }
    // The outer waves are summed as one pair, so that the mirrored problem adds the
    // same two numbers: the flux is then exactly mirror-symmetric in floating point.
    const auto component = [&](double Conserved::*q) {
        const double outer = w[0] * (fan.flux[1].*q - fan.flux[0].*q) + w[2] * (fan.flux[3].*q - fan.flux[2].*q);
        return 0.5 * (fan.flux[0].*q + fan.flux[3].*q) - outer - w[1] * (fan.flux[2].*q - fan.flux[1].*q);
    };
    return {component(&Conserved::h), component(&Conserved::qn), component(&Conserved::qt)};
}

}  // namespace avalanche
