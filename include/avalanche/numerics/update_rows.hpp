#pragma once
// The last two stages of the advection (advection.cpp) on one grid row, written for
// the vector units like the face kernels (face_flux_rows.hpp): the donor factors of
// the positivity-preserving flux scaling, and the conservative update with the
// invariant-domain clamp and the energy cap. Each is the scalar loop body with its
// branches turned into selections; the rare cases (a velocity outside the cell's own
// invariant bounds, which needs the eight neighbours, or over the energy cap; a cell
// the step would empty, for the donor factors) are finished by the scalar code
// afterwards. Results are bitwise those of the scalar loops
// (tests/regression/test_update_rows.cpp).
//
// All pointers address column 0 of the row; the row above is at +stride, the one
// below at -stride (the stage buffers and the grid fields share the row stride).
#include <cstddef>

namespace avalanche {

// The donor factor of the face whose mass flux is fh: the factor of the cell the mass
// leaves (below / left when fh > 0, else above / right); a zero mass flux has no donor
// (its momentum, the pressure of a wall face, passes unscaled).
inline double donor_factor_of(double fh, double factor_before, double factor_after) noexcept {
    return fh == 0.0 ? 1.0 : (fh > 0.0 ? factor_before : factor_after);
}

struct FaceFluxRows {
    const double *fx_h, *fx_hu, *fx_hv;  // x-faces: face i lies left of cell i
    const double *fy_h, *fy_hu, *fy_hv;  // y-faces: face (i, r) lies below cell (i, r)
};

// factor(i) = 0 if h < h_min; h / out if the cell would export out > h in the step;
// 1 otherwise, for cells i0 .. i1 - 1.
void donor_factor_row(const FaceFluxRows& f, const double* h, double rx, double ry, double h_min,
                      std::ptrdiff_t stride, double* factor, int i0, int i1) noexcept;

struct UpdateRowInput {
    FaceFluxRows f;
    const double* factor;                                // donor factors (rows r-1..r+1)
    const double *u_lo, *u_hi, *v_lo, *v_hi, *speed_hi;  // invariant bounds (rows r-1..r+1)
    const double *h, *hu, *hv;                           // the state before the update
    const double *elevation, *sx, *sy;                   // sx, sy null in bed-fitted frames
};

struct UpdateRowParams {
    double rx, ry;          // tau / dx, tau / dy
    std::ptrdiff_t stride;  // row stride of every array
    double energy_budget;   // per unit mass; the cap speed^2 is 2 (budget - g z)
    double gravity;
    // The thin-layer depth: a cell left thinner has its velocity set by the thin-layer
    // rule after the advection (Stepper::thin_layer_velocities), whatever the update
    // gives it, so the update gives it none (zero momentum) and spends nothing on its
    // bounds. 0 keeps every cell's bounds.
    double h_thin = 0.0;
};

// U -= rx dF + ry dG with the donor-scaled fluxes, then the velocity clamps and the
// energy cap, for cells i0 .. i1 - 1; writes the updated (h, hu, hv), with zero
// momentum where the new depth is below p.h_thin. In place if asked (h_new == in.h,
// hu_new == in.hu, hv_new == in.hv): a cell's update reads no other cell's state.
void update_row(const UpdateRowInput& in, const UpdateRowParams& p, double* h_new, double* hu_new,
                double* hv_new, int i0, int i1) noexcept;

}  // namespace avalanche
