#include "avalanche/numerics/rest_faces.hpp"

#include <vector>

#include "simd_clones.hpp"

namespace avalanche {

namespace {

// Whether a cell counts as dry for the test: thinner than h_min (or empty).
AVALANCHE_INLINE bool dry(double h, double h_min) { return !(h >= h_min) | !(h > 0.0); }

// The faces that may be held: both sides held or dry, and material on at least one; a
// face with a moving cell, or between two dry ones, keeps the scheme's flux. For each
// candidate the weight of its left cell's terrain (1 if the right cell is dry, 0 if the
// left one is, else 1/2: a dry cell's slope does not act on the material), -1 for the
// other faces. A plain loop over the flags, whose bytes the AVX-512F version of a vector
// loop could not mix with doubles (no byte vectors without AVX-512BW): the vector loop
// below reads the weights. Returns whether any face is a candidate.
bool candidate_faces(const RestFaceRowInput& in, double h_min, double* weight_l, int f0, int f1) {
    bool any = false;
    for (int f = f0; f < f1; ++f) {
        const bool dry_l = dry(in.h_l[f], h_min), dry_r = dry(in.h_r[f], h_min);
        const bool c =
            !(dry_l && dry_r) && (dry_l || in.held_l[f] != 0) && (dry_r || in.held_r[f] != 0);
        weight_l[f] = !c ? -1.0 : (dry_l ? 0.0 : (dry_r ? 1.0 : 0.5));
        any = any || c;
    }
    return any;
}

// hold_rest_faces_row's test with its branches turned into selections, so that it runs
// in the vector units like the face kernels (face_flux_rows.cpp): every lane computes the
// test, quotients of non-candidate lanes included, and the weights select.
template <bool Metric>
AVALANCHE_SIMD_CLONES int hold_clone(const RestFaceRowInput& in, const RestFaceRowParams& p,
                                     const double* __restrict weight_l, double* __restrict fh,
                                     double* __restrict fn, double* __restrict ft, int f0, int f1) {
    const double inv_dn = p.inv_dn, tan_delta = p.tan_delta;
    const double* __restrict h_l = in.h_l;
    const double* __restrict h_r = in.h_r;
    int held = 0;
#pragma omp simd reduction(+ : held)
    for (int f = f0; f < f1; ++f) {
        const double hl = h_l[f], hr = h_r[f];
        const double wl = weight_l[f], wr = 1.0 - wl;
        // The static driving acceleration across the face: gravity along the bed and the
        // face's pressure gradient -(P_r - P_l) / (dn (h_l + h_r) / 2), P = c h^2 / 2 (for
        // uniform c, -c dh/dn); along the face, gravity alone (the pressure gradients
        // along it act on the faces across it).
        const double pl = 0.5 * in.c_l[f] * hl * hl, pr = 0.5 * in.c_r[f] * hr * hr;
        const double an =
            wl * in.an_l[f] + wr * in.an_r[f] - (pr - pl) * inv_dn / (0.5 * (hl + hr));
        const double at = wl * in.at_l[f] + wr * in.at_r[f];
        double drive2 = an * an + at * at;
        if constexpr (Metric) {
            // In the DEM frame (horizontal velocity) the along-surface magnitude, as the
            // friction stage measures the speed it stops (cell_rows.cpp).
            const double w =
                (wl * in.sn_l[f] + wr * in.sn_r[f]) * an + (wl * in.st_l[f] + wr * in.st_r[f]) * at;
            drive2 += w * w;
        }
        const double limit = tan_delta * (wl * in.gn_l[f] + wr * in.gn_r[f]);
        // Strictly below the limit: without friction (delta = 0) no face is held.
        const bool hold = (wl >= 0.0) & (drive2 < limit * limit);
        fh[f] = hold ? 0.0 : fh[f];
        ft[f] = hold ? 0.0 : ft[f];
        fn[f] = hold ? 0.5 * (pl + pr) : fn[f];
        held += hold ? 1 : 0;
    }
    return held;
}

}  // namespace

int hold_rest_faces_row(const RestFaceRowInput& in, const RestFaceRowParams& p, double* fh,
                        double* fn, double* ft, int f0, int f1) noexcept {
    thread_local std::vector<double> weight_l;
    if (weight_l.size() < static_cast<std::size_t>(f1))
        weight_l.resize(static_cast<std::size_t>(f1));
    // Most rows of a moving flow hold no cell at rest: nothing to test there.
    if (!candidate_faces(in, p.h_min, weight_l.data(), f0, f1)) return 0;
    return in.sn_l != nullptr ? hold_clone<true>(in, p, weight_l.data(), fh, fn, ft, f0, f1)
                              : hold_clone<false>(in, p, weight_l.data(), fh, fn, ft, f0, f1);
}

void keep_held_at_rest(const HeldFlag* held, const double* fx_h, const double* fy_h,
                       std::ptrdiff_t stride, double* hu, double* hv, HeldFlag* held_next, int i0,
                       int i1) noexcept {
    for (int i = i0; i < i1; ++i) {
        const bool quiet =
            (fx_h[i] == 0.0) & (fx_h[i + 1] == 0.0) & (fy_h[i] == 0.0) & (fy_h[i + stride] == 0.0);
        const bool still = quiet & (held[i] != 0);
        if (still) {
            hu[i] = 0.0;
            hv[i] = 0.0;
        }
        if (held_next != nullptr) held_next[i] = still ? 1 : 0;
    }
}

void held_at_rest_row(const double* h, const double* hu, const double* hv, double h_min,
                      HeldFlag* held, int i0, int i1) noexcept {
    for (int i = i0; i < i1; ++i)
        held[i] = !dry(h[i], h_min) & (hu[i] == 0.0) & (hv[i] == 0.0) ? 1 : 0;
}

}  // namespace avalanche
