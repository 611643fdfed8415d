#include "avalanche/numerics/rest_faces.hpp"

#include <algorithm>

#include "avalanche/physics/dem_coefficients.hpp"
#include "simd_clones.hpp"

namespace avalanche {

namespace {

// Whether a cell counts as dry for the test: thinner than h_min (or empty).
AVALANCHE_INLINE bool dry(double h, double h_min) { return !(h >= h_min) | !(h > 0.0); }

// A candidate face has both sides held or dry and material on at least one; a face
// with a moving cell, or between two dry ones, keeps the scheme's flux. The caller's
// dry tests of the face's cells (the test needs them again for the weights).
AVALANCHE_INLINE bool candidate_face(const RestFaceRowInput& in, bool dry_l, bool dry_r, int f) {
    const bool material = !(dry_l & dry_r);
    return material & (dry_l | (in.held_l[f] != 0)) & (dry_r | (in.held_r[f] != 0));
}

// hold_rest_faces_row's test with its branches turned into selections, so that it runs
// in the vector units like the face kernels (face_flux_rows.cpp): every lane computes the
// test, quotients of non-candidate lanes included, and the candidates select. A
// candidate's left cell's terrain weighs 1 if the right cell is dry, 0 if the left one
// is, else 1/2: a dry cell's slope does not act on the material.
// A cell's normal and tangential source accelerations and its bed-normal gravity: read,
// or in the DEM frame computed from its slopes (normal sn, tangential st) as the terrain
// computes them (dem_coefficients with z_x the x-slope: sn on x-faces, st on y-faces).
struct CellDrive {
    double an, at, gn;
};

template <bool Metric, bool XFaces>
AVALANCHE_INLINE CellDrive cell_drive(const double* an, const double* at, const double* gn,
                                      const double* sn, const double* st, double g, int f) {
    if constexpr (Metric) {
        const DemCoefficients c =
            XFaces ? dem_coefficients(sn[f], st[f], g) : dem_coefficients(st[f], sn[f], g);
        return {XFaces ? c.ax : c.ay, XFaces ? c.ay : c.ax, c.gn};
    } else {
        return {an[f], at[f], gn[f]};
    }
}

template <bool Metric, bool XFaces>
AVALANCHE_INLINE int hold_block(const RestFaceRowInput& in, const RestFaceRowParams& p,
                                double* __restrict fh, double* __restrict fn, double* __restrict ft,
                                int f0, int f1) {
    const double inv_dn = p.inv_dn, tan_delta = p.tan_delta, h_min = p.h_min;
    const double g = in.slope_gravity;
    const double* __restrict h_l = in.h_l;
    const double* __restrict h_r = in.h_r;
    int held = 0;
#pragma omp simd reduction(+ : held)
    for (int f = f0; f < f1; ++f) {
        const double hl = h_l[f], hr = h_r[f];
        const bool dry_l = dry(hl, h_min), dry_r = dry(hr, h_min);
        const bool candidate = candidate_face(in, dry_l, dry_r, f);
        const double wl = dry_l ? 0.0 : (dry_r ? 1.0 : 0.5), wr = 1.0 - wl;
        // The static driving acceleration across the face: gravity along the bed and the
        // face's pressure gradient -(P_r - P_l) / (dn (h_l + h_r) / 2), P = c h^2 / 2 (for
        // uniform c, -c dh/dn); along the face, gravity alone (the pressure gradients
        // along it act on the faces across it).
        const double pl = 0.5 * in.c_l[f] * hl * hl, pr = 0.5 * in.c_r[f] * hr * hr;
        const CellDrive dl = cell_drive<Metric, XFaces>(in.an_l, in.at_l, in.gn_l, in.sn_l, in.st_l, g, f);
        const CellDrive dr = cell_drive<Metric, XFaces>(in.an_r, in.at_r, in.gn_r, in.sn_r, in.st_r, g, f);
        const double an = wl * dl.an + wr * dr.an - (pr - pl) * inv_dn / (0.5 * (hl + hr));
        const double at = wl * dl.at + wr * dr.at;
        double drive2 = an * an + at * at;
        if constexpr (Metric) {
            // In the DEM frame (horizontal velocity) the along-surface magnitude, as the
            // friction stage measures the speed it stops (cell_rows.cpp).
            const double w =
                (wl * in.sn_l[f] + wr * in.sn_r[f]) * an + (wl * in.st_l[f] + wr * in.st_r[f]) * at;
            drive2 += w * w;
        }
        const double limit = tan_delta * (wl * dl.gn + wr * dr.gn);
        // Strictly below the limit: without friction (delta = 0) no face is held.
        const bool hold = candidate & (drive2 < limit * limit);
        fh[f] = hold ? 0.0 : fh[f];
        ft[f] = hold ? 0.0 : ft[f];
        fn[f] = hold ? 0.5 * (pl + pr) : fn[f];
        held += hold ? 1 : 0;
    }
    return held;
}

// The faces in blocks of kBlock: a block without a candidate (most of a moving flow) is
// not tested. The flags are bytes, which the vector loops read in the AVX-512 clone
// since it has byte vectors (x86-64-v4, simd_clones.hpp); with AVX-512F alone they
// would not vectorise.
constexpr int kBlock = 32;

template <bool Metric, bool XFaces>
AVALANCHE_SIMD_CLONES int hold_clone(const RestFaceRowInput& in, const RestFaceRowParams& p,
                                     double* __restrict fh, double* __restrict fn,
                                     double* __restrict ft, int f0, int f1) {
    const double h_min = p.h_min;
    int held = 0;
    for (int b0 = f0; b0 < f1; b0 += kBlock) {
        const int b1 = std::min(b0 + kBlock, f1);
        int candidates = 0;
#pragma omp simd reduction(+ : candidates)
        for (int f = b0; f < b1; ++f) {
            const bool dry_l = dry(in.h_l[f], h_min), dry_r = dry(in.h_r[f], h_min);
            candidates += candidate_face(in, dry_l, dry_r, f) ? 1 : 0;
        }
        if (candidates > 0) held += hold_block<Metric, XFaces>(in, p, fh, fn, ft, b0, b1);
    }
    return held;
}

// keep_held_at_rest's loop, vectorised (the flags as above); with or without the next
// advection's flags.
template <bool Next>
AVALANCHE_SIMD_CLONES void keep_clone(const HeldFlag* __restrict held,
                                      const double* __restrict fx_h, const double* __restrict fy_h,
                                      std::ptrdiff_t stride, double* __restrict hu,
                                      double* __restrict hv, HeldFlag* __restrict held_next, int i0,
                                      int i1) {
#pragma omp simd
    for (int i = i0; i < i1; ++i) {
        const bool quiet =
            (fx_h[i] == 0.0) & (fx_h[i + 1] == 0.0) & (fy_h[i] == 0.0) & (fy_h[i + stride] == 0.0);
        const bool still = quiet & (held[i] != 0);
        hu[i] = still ? 0.0 : hu[i];
        hv[i] = still ? 0.0 : hv[i];
        if constexpr (Next) held_next[i] = still ? 1 : 0;
    }
}

// held_at_rest_row's loop, vectorised.
AVALANCHE_SIMD_CLONES void held_clone(const double* __restrict h, const double* __restrict hu,
                                      const double* __restrict hv, double h_min,
                                      HeldFlag* __restrict held, int i0, int i1) {
#pragma omp simd
    for (int i = i0; i < i1; ++i) {
        const bool wet = !dry(h[i], h_min);
        held[i] = (wet & (hu[i] == 0.0) & (hv[i] == 0.0)) ? 1 : 0;
    }
}

}  // namespace

int hold_rest_faces_row(const RestFaceRowInput& in, const RestFaceRowParams& p, double* fh,
                        double* fn, double* ft, int f0, int f1) noexcept {
    if (in.sn_l == nullptr) return hold_clone<false, true>(in, p, fh, fn, ft, f0, f1);
    return in.x_faces ? hold_clone<true, true>(in, p, fh, fn, ft, f0, f1)
                      : hold_clone<true, false>(in, p, fh, fn, ft, f0, f1);
}

void keep_held_at_rest(const HeldFlag* held, const double* fx_h, const double* fy_h,
                       std::ptrdiff_t stride, double* hu, double* hv, HeldFlag* held_next, int i0,
                       int i1) noexcept {
    if (held_next != nullptr)
        keep_clone<true>(held, fx_h, fy_h, stride, hu, hv, held_next, i0, i1);
    else
        keep_clone<false>(held, fx_h, fy_h, stride, hu, hv, held_next, i0, i1);
}

void held_at_rest_row(const double* h, const double* hu, const double* hv, double h_min,
                      HeldFlag* held, int i0, int i1) noexcept {
    held_clone(h, hu, hv, h_min, held, i0, i1);
}

}  // namespace avalanche
