#include "avalanche/numerics/face_flux_rows.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "avalanche/numerics/riemann_hllc.hpp"
#include "simd_clones.hpp"

namespace avalanche {

namespace {

// A face's first-order flux, the expressions of hllc_flux(ql, qr, c_l, c_r, h_dry)
// (riemann_hllc.hpp) with its branches turned into selections.
struct FaceFlux {
    double h, qn, qt;
};

// The side velocities come in as the quotients q / h of every cell (ul_any = qn_l / h_l,
// ...), computed by the caller once per cell; a dry side's quotient is discarded. The
// celerities al = sqrt(c_l h_l), ar (0 on a dry side) come per cell too (celerity_row).
AVALANCHE_INLINE FaceFlux hllc_lane(double h_l, double ul_any, double vl_any, double h_r,
                                    double ur_any, double vr_any, double c_l, double c_r,
                                    double al, double ar, double h_dry) {
    // Non-short-circuit logic and divisions evaluated for every lane: conditional
    // arithmetic would keep the loop scalar.
    const bool wet_l = is_wet(h_l, h_dry);
    const bool wet_r = is_wet(h_r, h_dry);
    const double hl = wet_l ? h_l : 0.0, hr = wet_r ? h_r : 0.0;
    const double ul = wet_l ? ul_any : 0.0, vl = wet_l ? vl_any : 0.0;
    const double ur = wet_r ? ur_any : 0.0, vr = wet_r ? vr_any : 0.0;
    // The three speed cases of the scalar kernel: right side dry, left side dry, both wet.
    const double s_l_wet = std::min(ul - al, ur - ar);
    const double s_r_wet = std::max(ul + al, ur + ar);
    const double s_star_wet = (s_l_wet * hr * (ur - s_r_wet) - s_r_wet * hl * (ul - s_l_wet)) /
                              (hr * (ur - s_r_wet) - hl * (ul - s_l_wet));
    const double front_r = ul + 2.0 * al, front_l = ur - 2.0 * ar;
    const double s_l = !wet_r ? ul - al : (!wet_l ? front_l : s_l_wet);
    const double s_star = !wet_r ? front_r : (!wet_l ? front_l : s_star_wet);
    const double s_r = !wet_r ? front_r : (!wet_l ? ur + ar : s_r_wet);

    const Conserved fl = physical_flux(hl, ul, vl, c_l), fr = physical_flux(hr, ur, vr, c_r);
    const double inv = 1.0 / (s_r - s_l);
    const double fh = (s_r * fl.h - s_l * fr.h + s_l * s_r * (hr - hl)) * inv;
    const double fq = (s_r * fl.qn - s_l * fr.qn + s_l * s_r * (hr * ur - hl * ul)) * inv;
    const double ft = fh * (s_star >= 0.0 ? vl : vr);

    const bool left = s_l >= 0.0;
    const bool right = !left & (s_star < 0.0) & (s_r < 0.0);
    const bool dry = !wet_l & !wet_r;
    FaceFlux f;
    f.h = dry ? 0.0 : (left ? fl.h : (right ? fr.h : fh));
    f.qn = dry ? 0.0 : (left ? fl.qn : (right ? fr.qn : fq));
    f.qt = dry ? 0.0 : (left ? fl.qt : (right ? fr.qt : ft));
    return f;
}

template <Limiter L>
AVALANCHE_INLINE double psi_of(double r) {
    double p = 0.0;
    if constexpr (L == Limiter::superbee) {
        p = std::max(std::min(2.0 * r, 1.0), std::min(r, 2.0));
    } else if constexpr (L == Limiter::van_leer) {
        p = 2.0 * r / (1.0 + r);
    } else if constexpr (L == Limiter::van_albada) {
        p = r * (1.0 + r) / (1.0 + r * r);
    } else {
        p = std::min(r, 1.0);
    }
    return r <= 0.0 ? 0.0 : p;  // limiter_psi (limiters.hpp)
}

// x sign(y): x with its sign bit flipped where y's is set (exact, and no comparison).
AVALANCHE_INLINE double times_sign_of(double x, double y) {
    constexpr std::uint64_t kSign = std::uint64_t{1} << 63;
    return std::bit_cast<double>(std::bit_cast<std::uint64_t>(x) ^
                                 (std::bit_cast<std::uint64_t>(y) & kSign));
}

// jump_ratio (limiters.hpp) as selections.
AVALANCHE_INLINE double ratio_of(double d_upwind, double d_local, double tiny) {
    const double flat = std::abs(d_upwind) <= tiny ? 1.0 : 0.0;
    const double r = d_upwind / d_local;
    return std::abs(d_local) <= tiny ? flat : r;
}

// limiter_psi_of_jumps (limiters.hpp) as selections.
template <Limiter L>
AVALANCHE_INLINE double psi_of_jumps(double d_upwind, double d_local, double tiny) {
    if constexpr (L == Limiter::van_leer) {
        // 2 d_up / (d_local + d_up) where the jumps share a sign, else 0, as
        // (sign(d_local) d_up + |d_up|) / (|d_local| + |d_up|): the numerator is 2 |d_up|
        // or exactly 0, the same bits without the four sign tests and their masks (the
        // WAF face's time follows its instruction count: docs/performance.md).
        const double up_abs = std::abs(d_upwind), local_abs = std::abs(d_local);
        const double flat = up_abs <= tiny ? 1.0 : 0.0;
        const double p = (times_sign_of(d_upwind, d_local) + up_abs) / (local_abs + up_abs);
        return local_abs <= tiny ? flat : p;
    } else {
        return psi_of<L>(ratio_of(d_upwind, d_local, tiny));
    }
}

// The WAF weight 1/2 sign(c) A of one wave (waf_flux, riemann_hllc.hpp), from
// c / 2 = s (dt / 2dx) clamped to [-1/2, 1/2]: 1/2 A = 1/2 - (1/2 - |c / 2|) psi, the
// same bits as halving A (halving is exact away from subnormals). The clamp acts on
// |c / 2| alone (one minimum) and the sign is c's bit: one comparison instead of four
// and their selections.
AVALANCHE_INLINE double waf_weight(double s, double half_dt_over_dx, double psi) {
    const double half_c = s * half_dt_over_dx;
    const double half_c_abs = std::min(std::abs(half_c), 0.5);
    const double half_a = 0.5 - (0.5 - half_c_abs) * psi;
    return half_c == 0.0 ? 0.0 : times_sign_of(half_a, half_c);
}

AVALANCHE_INLINE double waf_component(double f0, double f1, double f2, double f3,
                                      const double w[3]) {
    const double outer = w[0] * (f1 - f0) + w[2] * (f3 - f2);
    return 0.5 * (f0 + f3) - outer - w[1] * (f2 - f1);
}

// waf_component(f0, f_star, f_star, f3, w) for a component that does not jump across
// the contact (h, q_n): w[1] (f_star - f_star) is a zero with w[1]'s sign (f_star is
// finite here or the whole flux is NaN either way), subtracted as such to keep the bits.
AVALANCHE_INLINE double waf_component_no_contact(double f0, double f_star, double f3,
                                                 const double w[3]) {
    const double outer = w[0] * (f_star - f0) + w[2] * (f3 - f_star);
    return 0.5 * (f0 + f3) - outer - times_sign_of(0.0, w[1]);
}

// waf_face_flux (waf_face.hpp) for one face with all four stencil cells at least
// h_dry thick (so both sides wet, h_dry > 0): hllc_fan's wet/wet fan, the
// wave-strength and shear limiter ratios, waf_flux. The cells' velocities come in as
// the quotients q / h (ul = qn_l / h_l, vl = qt_l / h_l, v_ll = qt_ll / h_ll, ...), the
// celerities al = sqrt(c_l h_l), ar = sqrt(c_r h_r) per cell (celerity_row).
template <Limiter L>
AVALANCHE_INLINE FaceFlux waf_lane(double h_ll, double qn_ll, double v_ll, double h_l, double qn_l,
                                   double ul, double vl, double h_r, double qn_r, double ur,
                                   double vr, double h_rr, double qn_rr, double v_rr, double c_l,
                                   double c_r, double al, double ar, double dt_over_dx) {
    constexpr double kFlat = 1e-12;  // waf_face_flux (waf_face.hpp)
    const double s_l = std::min(ul - al, ur - ar);
    const double s_r = std::max(ul + al, ur + ar);
    const double s_star =
        (s_l * h_r * (ur - s_r) - s_r * h_l * (ul - s_l)) / (h_r * (ur - s_r) - h_l * (ul - s_l));
    const Conserved f0 = physical_flux(h_l, ul, vl, c_l), f3 = physical_flux(h_r, ur, vr, c_r);
    const double inv = 1.0 / (s_r - s_l);
    const double fh = (s_r * f0.h - s_l * f3.h + s_l * s_r * (h_r - h_l)) * inv;
    const double fq = (s_r * f0.qn - s_l * f3.qn + s_l * s_r * (h_r * ur - h_l * ul)) * inv;
    const double f1t = fh * vl, f2t = fh * vr;

    const double h_bar = 0.5 * (h_l + h_r);
    const double u_bar = 0.5 * (ul + ur);
    const double a_bar = std::sqrt(0.5 * (c_l + c_r) * h_bar);
    const double tiny_alpha = kFlat * h_bar * (2.0 * a_bar);
    const double up_l = u_bar + a_bar, up_r = u_bar - a_bar;
    // Outer waves: strengths 2a alpha_1 = (u + a) dh - dq, 2a alpha_3 = dq - (u - a) dh
    // (the limiter reads their ratio; waf_face.hpp).
    const double dh_loc = h_r - h_l, dq_loc = qn_r - qn_l;
    const double dh_lup = h_l - h_ll, dq_lup = qn_l - qn_ll;  // the face upwind on the left
    const double dh_rup = h_rr - h_r, dq_rup = qn_rr - qn_r;  // the face upwind on the right
    // The upwind face's jumps are selected before they are weighted: one product per
    // wave instead of two.
    const bool from_left_1 = s_l >= 0.0;
    const double loc_1 = up_l * dh_loc - dq_loc;
    const double dh_up_1 = from_left_1 ? dh_lup : dh_rup, dq_up_1 = from_left_1 ? dq_lup : dq_rup;
    const double up_1 = up_l * dh_up_1 - dq_up_1;
    const bool from_left_3 = s_r >= 0.0;
    const double loc_3 = dq_loc - up_r * dh_loc;
    const double dh_up_3 = from_left_3 ? dh_lup : dh_rup, dq_up_3 = from_left_3 ? dq_lup : dq_rup;
    const double up_3 = dq_up_3 - up_r * dh_up_3;
    // Shear wave: the jump of the transverse velocity.
    const bool from_left_2 = s_star >= 0.0;
    // The upwind cell's transverse velocity (of LL or RR): the scalar kernel's
    // velocity_or_zero is the quotient itself on every face this flux is kept for (all
    // four stencil cells at least h_dry > 0 thick; the callers select the first-order
    // flux on the others).
    const double v_up = from_left_2 ? v_ll : v_rr;
    const double dv_loc = vr - vl;
    const double dv_up = from_left_2 ? vl - v_up : v_up - vr;
    const double tiny_v = kFlat * std::max(std::abs(vl), std::abs(vr));

    const double psi1 = psi_of_jumps<L>(up_1, loc_1, tiny_alpha);
    const double psi2 = psi_of_jumps<L>(dv_up, dv_loc, tiny_v);
    const double psi3 = psi_of_jumps<L>(up_3, loc_3, tiny_alpha);
    const double half_dt_over_dx = 0.5 * dt_over_dx;  // loop-invariant: hoisted
    const double w[3] = {waf_weight(s_l, half_dt_over_dx, psi1),
                         waf_weight(s_star, half_dt_over_dx, psi2),
                         waf_weight(s_r, half_dt_over_dx, psi3)};
    return {waf_component_no_contact(f0.h, fh, f3.h, w),
            waf_component_no_contact(f0.qn, fq, f3.qn, w),
            waf_component(f0.qt, f1t, f2t, f3.qt, w)};
}

AVALANCHE_INLINE void hllc_row(const FaceRowInput& in, const FaceRowOutput& out, int n,
                               double h_dry) {
    const std::ptrdiff_t off = in.off;
    const double* __restrict h = in.h;
    const double* __restrict un = in.un;
    const double* __restrict ut = in.ut;
    const double* __restrict c = in.c;
    const double* __restrict a = in.a;
    double* __restrict oh = out.h;
    double* __restrict oqn = out.qn;
    double* __restrict oqt = out.qt;
#pragma omp simd
    for (int i = 0; i < n; ++i) {
        const FaceFlux f = hllc_lane(h[i - off], un[i - off], ut[i - off], h[i], un[i], ut[i],
                                     c[i - off], c[i], a[i - off], a[i], h_dry);
        oh[i] = f.h;
        oqn[i] = f.qn;
        oqt[i] = f.qt;
    }
}

// Whether both cells beside a face are thinner than h_dry: then the first-order flux is
// zero (hllc_flux's two dry sides), and so is the WAF kernel's, which takes the
// first-order flux at a front. Ordered comparisons, false for NaN: a NaN beside a face
// leaves it to the kernels, whatever they make of it.
// As 1.0 or 0.0, a product of selections: GCC 12 turned the '&' of the two comparisons
// into branches and left the loops over a row scalar (a fifth of the WAF kernel's time).
AVALANCHE_INLINE double dry_face_flag(double h_l, double h_r, double h_dry) {
    return (h_l < h_dry ? 1.0 : 0.0) * (h_r < h_dry ? 1.0 : 0.0);
}
AVALANCHE_INLINE bool dry_face(double h_l, double h_r, double h_dry) {
    return dry_face_flag(h_l, h_r, h_dry) != 0.0;
}

// The input of a row's faces from face a on.
AVALANCHE_INLINE FaceRowInput from_face(const FaceRowInput& in, int a) {
    FaceRowInput sub = in;
    sub.h += a;
    sub.qn += a;
    sub.qt += a;
    sub.c += a;
    sub.un += a;
    sub.ut += a;
    sub.a += a;
    return sub;
}

// The zero fluxes of the dry faces a .. b - 1.
AVALANCHE_INLINE void write_zero_fluxes(const FaceRowOutput& out, int a, int b) {
    std::fill(out.h + a, out.h + b, 0.0);
    std::fill(out.qn + a, out.qn + b, 0.0);
    std::fill(out.qt + a, out.qt + b, 0.0);
}

// What each face's flux takes, from its stencil's depths: 0 for a dry face (dry_face),
// 2 where none of the four stencil cells is thinner than h_dry (the WAF flux; a NaN
// may drop out of the minimum, as it passes the scalar kernel's front test), 1 for the
// others (at or near a wet/dry front: both fluxes, selected face by face).
AVALANCHE_INLINE void stencil_kinds(const FaceRowInput& in, int n, double h_dry,
                                    double* __restrict kind) {
    const std::ptrdiff_t off = in.off;
    const double* __restrict h = in.h;
#pragma omp simd
    for (int i = 0; i < n; ++i) {
        const double thin =
            std::min(std::min(h[i - 2 * off], h[i - off]), std::min(h[i], h[i + off]));
        // A sum of flags, not nested selections (GCC 12 left those scalar, as it did
        // std::min of local copies); a dry face's thinnest cell is thinner than h_dry.
        kind[i] = (1.0 - dry_face_flag(h[i - off], h[i], h_dry)) + (thin >= h_dry ? 1.0 : 0.0);
    }
}

template <Limiter L, bool Fronts>
AVALANCHE_INLINE void waf_row(const FaceRowInput& in, const FaceRowOutput& out, int n, double h_dry,
                              double dt_over_dx) {
    const std::ptrdiff_t off = in.off;
    const double* __restrict h = in.h;
    const double* __restrict qn = in.qn;
    const double* __restrict un = in.un;
    const double* __restrict ut = in.ut;
    const double* __restrict c = in.c;
    const double* __restrict a = in.a;
    double* __restrict oh = out.h;
    double* __restrict oqn = out.qn;
    double* __restrict oqt = out.qt;
#pragma omp simd
    for (int i = 0; i < n; ++i) {
        const double hll = h[i - 2 * off], hl = h[i - off], hr = h[i], hrr = h[i + off];
        const double ul = un[i - off], vl = ut[i - off], ur = un[i], vr = ut[i];
        const FaceFlux w = waf_lane<L>(hll, qn[i - 2 * off], ut[i - 2 * off], hl, qn[i - off], ul,
                                       vl, hr, qn[i], ur, vr, hrr, qn[i + off], ut[i + off],
                                       c[i - off], c[i], a[i - off], a[i], dt_over_dx);
        if constexpr (Fronts) {
            // At a wet/dry front (a stencil cell thinner than h_dry) the first-order flux.
            const bool front = (hll < h_dry) | (hl < h_dry) | (hr < h_dry) | (hrr < h_dry);
            const FaceFlux g =
                hllc_lane(hl, ul, vl, hr, ur, vr, c[i - off], c[i], a[i - off], a[i], h_dry);
            oh[i] = front ? g.h : w.h;
            oqn[i] = front ? g.qn : w.qn;
            oqt[i] = front ? g.qt : w.qt;
        } else {
            oh[i] = w.h;
            oqn[i] = w.qn;
            oqt[i] = w.qt;
        }
    }
}

// The end of the run of faces from `from` of one kind (stencil_kinds): blocks of 16
// faces tested by vector compares, the block where the run ends face by face. A loop
// face by face cost a seventh of the kernel's time on a row without a front.
AVALANCHE_INLINE int run_end(const double* __restrict kind, int from, int n, double k) {
    constexpr int kBlock = 16;
    int b = from;
    for (; b + kBlock <= n; b += kBlock) {
        int other = 0;
#pragma omp simd reduction(| : other)
        for (int j = 0; j < kBlock; ++j) other |= kind[b + j] != k ? 1 : 0;
        if (other != 0) break;
    }
    while (b < n && kind[b] == k) ++b;
    return b;
}

// A thread's scratch row of at least n doubles, for the faces' kinds.
AVALANCHE_INLINE double* kind_scratch(int n) {
    thread_local std::vector<double> kind;
    if (kind.size() < static_cast<std::size_t>(n)) kind.resize(static_cast<std::size_t>(n));
    return kind.data();
}

// A row is cut into runs of faces of one kind (stencil_kinds): the faces between two dry
// cells get the zero flux the first-order kernel gives them without computing it (most
// of an active box on a real scene: the box bounds a flow that fills part of it), the
// faces without a front (the interior of a flow) skip the first-order flux their
// selection would discard, the others compute both and select per face.
template <Limiter L>
AVALANCHE_INLINE void waf_row_dispatch(const FaceRowInput& in, const FaceRowOutput& out, int n,
                                       double h_dry, double dt_over_dx) {
    double* kind = kind_scratch(n);
    stencil_kinds(in, n, h_dry, kind);
    // A loop, not a helper taking the run as a lambda: with the lambda GCC 12 left
    // waf_row scalar (3x the time, bench_row_kernels).
    for (int a = 0; a < n;) {
        const double k = kind[a];
        const int b = run_end(kind, a + 1, n, k);
        if (k == 0.0) {
            write_zero_fluxes(out, a, b);
        } else {
            const FaceRowInput sub = from_face(in, a);
            const FaceRowOutput to{out.h + a, out.qn + a, out.qt + a};
            if (k == 1.0)
                waf_row<L, true>(sub, to, b - a, h_dry, dt_over_dx);
            else
                waf_row<L, false>(sub, to, b - a, h_dry, dt_over_dx);
        }
        a = b;
    }
}

AVALANCHE_SIMD_CLONES void waf_row_superbee(const FaceRowInput& in, const FaceRowOutput& out, int n,
                                            double h_dry, double dt_over_dx) {
    waf_row_dispatch<Limiter::superbee>(in, out, n, h_dry, dt_over_dx);
}
AVALANCHE_SIMD_CLONES void waf_row_van_leer(const FaceRowInput& in, const FaceRowOutput& out, int n,
                                            double h_dry, double dt_over_dx) {
    waf_row_dispatch<Limiter::van_leer>(in, out, n, h_dry, dt_over_dx);
}
AVALANCHE_SIMD_CLONES void waf_row_van_albada(const FaceRowInput& in, const FaceRowOutput& out,
                                              int n, double h_dry, double dt_over_dx) {
    waf_row_dispatch<Limiter::van_albada>(in, out, n, h_dry, dt_over_dx);
}
AVALANCHE_SIMD_CLONES void waf_row_minmod(const FaceRowInput& in, const FaceRowOutput& out, int n,
                                          double h_dry, double dt_over_dx) {
    waf_row_dispatch<Limiter::minmod>(in, out, n, h_dry, dt_over_dx);
}
// 0 for the dry faces (dry_face), 1 for the others.
AVALANCHE_SIMD_CLONES void dry_kinds_any(const double* __restrict h, std::ptrdiff_t off, int n,
                                         double h_dry, double* __restrict kind) {
#pragma omp simd
    for (int i = 0; i < n; ++i) kind[i] = 1.0 - dry_face_flag(h[i - off], h[i], h_dry);
}

AVALANCHE_SIMD_CLONES void hllc_row_any(const FaceRowInput& in, const FaceRowOutput& out, int n,
                                        double h_dry) {
    hllc_row(in, out, n, h_dry);
}

// The first-order row cut into runs of dry faces (dry_face: their zero flux written, not
// computed) and of the others, where the row begins or ends with a dry face: the rows of
// an active box around a real flow, which the flow fills in their middle. A row that
// begins and ends wet is computed whole, as a fully wet flow's rows are: telling its
// dry faces apart first cost 12 % on such a row (bench_row_kernels), and dry faces
// inside it are computed, to the same zeros. (The runs are computed by the clones
// above: with the cutting in the same function GCC 12 left the kernel scalar.)
void hllc_row_by_runs(const FaceRowInput& in, const FaceRowOutput& out, int n, double h_dry) {
    const std::ptrdiff_t off = in.off;
    const double* h = in.h;
    if (n <= 0 || (!dry_face(h[-off], h[0], h_dry) && !dry_face(h[n - 1 - off], h[n - 1], h_dry))) {
        hllc_row_any(in, out, n, h_dry);
        return;
    }
    double* kind = kind_scratch(n);
    dry_kinds_any(h, off, n, h_dry, kind);
    for (int a = 0; a < n;) {
        const double k = kind[a];
        const int b = run_end(kind, a + 1, n, k);
        if (k == 0.0)
            write_zero_fluxes(out, a, b);
        else
            hllc_row_any(from_face(in, a), {out.h + a, out.qn + a, out.qt + a}, b - a, h_dry);
        a = b;
    }
}

AVALANCHE_SIMD_CLONES void celerity_row_any(const double* __restrict h, const double* __restrict c,
                                            double h_dry, double* __restrict a, int n) {
#pragma omp simd
    for (int i = 0; i < n; ++i) a[i] = side_celerity(h[i], c[i], h_dry);
}

// The quotient 0 / 0 of an emptied cell's stored values (NaN; the faces discard it).
constexpr double kEmptyQuotient = std::numeric_limits<double>::quiet_NaN();

AVALANCHE_SIMD_CLONES void predictor_row_any(const FaceRowInput& q, const FaceRowOutput& flux,
                                             double ratio, double h_dry, const FaceRowOutput& out,
                                             int n) {
    double* __restrict pun = out.un;
    double* __restrict put = out.ut;
    const std::ptrdiff_t off = q.off;
    const double* __restrict h = q.h;
    const double* __restrict qn = q.qn;
    const double* __restrict qt = q.qt;
    const double* __restrict un = q.un;
    const double* __restrict ut = q.ut;
    const double* __restrict fh = flux.h;
    const double* __restrict fqn = flux.qn;
    const double* __restrict fqt = flux.qt;
    double* __restrict ph = out.h;
    double* __restrict pqn = out.qn;
    double* __restrict pqt = out.qt;
#pragma omp simd
    for (int i = 0; i < n; ++i) {
        const double hh = h[i] - ratio * (fh[i + off] - fh[i]);
        const double hn = qn[i] - ratio * (fqn[i + off] - fqn[i]);
        const double ht = qt[i] - ratio * (fqt[i + off] - fqt[i]);
        const bool empty = hh <= 0.0;
        // A cell wet in the state (h >= h_dry) whose prediction falls below h_dry is
        // not predicted (it keeps its state): the faces take a thin predicted side as
        // dry, so a film cell just above h_dry, which loses a few per cent in the half
        // step, passed no flux in either direction, kept its mass and was accelerated
        // by gravity step after step (23 m/s on the chute's 45 deg slope, setting the
        // time step; docs/numerics.md, step 3). The prediction only feeds fluxes, and
        // the donor factors keep the cell from exporting more than it holds.
        // Its quotients are the state's (q.un, q.ut: the same divisions). The quotients
        // are divided from the unselected values: GCC turns a quotient of selected values
        // into masked divisions, which took twice the time (bench_row_kernels).
        const bool kept = (h[i] >= h_dry) & (hh < h_dry);
        const double inv = 1.0 / hh;
        const double un_p = hn * inv, ut_p = ht * inv;
        ph[i] = kept ? h[i] : (empty ? 0.0 : hh);
        pqn[i] = kept ? qn[i] : (empty ? 0.0 : hn);
        pqt[i] = kept ? qt[i] : (empty ? 0.0 : ht);
        pun[i] = kept ? un[i] : (empty ? kEmptyQuotient : un_p);  // the quotients of the values
        put[i] = kept ? ut[i] : (empty ? kEmptyQuotient : ut_p);
    }
}

}  // namespace

void celerity_row(const double* h, const double* c, double h_dry, double* a, int n) noexcept {
    celerity_row_any(h, c, h_dry, a, n);
}

void predictor_row(const FaceRowInput& q, const FaceRowOutput& flux, double ratio, double h_dry,
                   const FaceRowOutput& out, int n) noexcept {
    predictor_row_any(q, flux, ratio, h_dry, out, n);
}

void hllc_face_row(const FaceRowInput& in, const FaceRowOutput& out, int n, double h_dry) noexcept {
    hllc_row_by_runs(in, out, n, h_dry);
}

void waf_face_row(const FaceRowInput& in, const FaceRowOutput& out, int n, double h_dry,
                  double dt_over_dx, Limiter limiter) noexcept {
    switch (limiter) {
        case Limiter::superbee:
            waf_row_superbee(in, out, n, h_dry, dt_over_dx);
            return;
        case Limiter::van_leer:
            waf_row_van_leer(in, out, n, h_dry, dt_over_dx);
            return;
        case Limiter::van_albada:
            waf_row_van_albada(in, out, n, h_dry, dt_over_dx);
            return;
        case Limiter::minmod:
            waf_row_minmod(in, out, n, h_dry, dt_over_dx);
            return;
    }
}

}  // namespace avalanche
