#pragma once
// Face fluxes of one grid row, written for the vector units (SIMD): the stepper's
// hot loops (the predictor's first-order fluxes and the WAF fluxes, 70 % of the
// instructions of a fully wet step) call these once per row.
//
// Every value is computed by the same expressions, in the same order, as the scalar
// kernels of riemann_hllc.hpp and the limiter code of limiters.hpp, or by rearrangements
// that are exact in IEEE arithmetic (a factor 1/2 moved, a sign taken from a sign bit;
// face_flux_rows.cpp says where); the branches of the scalar code (wet/dry sides, fan
// region, wet/dry front, wave direction) become selections between values computed for
// every face, and faces between two dry cells get the scalar kernels' zero flux written
// without computing it. IEEE arithmetic is exact per operation and the core layer is
// built without FMA contraction, so the results are bitwise those of the scalar
// kernels, whatever vector width the machine has (tests/regression/test_face_flux_rows.cpp).
//
// Layout: one row of n faces; the pointers address the cell right of (above) the
// first face, and face m lies between the cells m - off and m of them, where off is
// 1 for x-faces and the row stride for y-faces; the outputs address the first face.
// The loads of both directions are contiguous in m. Inputs and outputs may live in
// arrays of different extents (the stepper's strip buffers) with the same stride. The "normal"
// momentum is hu for x-faces and hv for y-faces (the tangential one the other).
#include <cmath>
#include <cstddef>

#include "avalanche/numerics/parameters.hpp"

namespace avalanche {

struct FaceRowInput {
    const double* h;   // depth per cell (whole field, indexed by k)
    const double* qn;  // momentum normal to the faces
    const double* qt;  // momentum along the faces
    const double* c;   // pressure coefficient k g_z per cell
    std::ptrdiff_t off;
    // The quotients qn / h and qt / h per cell (inf or NaN where h = 0), computed once
    // per cell by the caller; required by the flux kernels, which read the velocities
    // from them (and qn for the WAF jumps), and by predictor_row (for the cells it
    // leaves unpredicted).
    const double* un = nullptr;
    const double* ut = nullptr;
    // The celerity sqrt(c h) of every cell at least h_dry thick, 0 on the others
    // (celerity_row); required by the flux kernels, which would otherwise take two
    // square roots per face for what is one per cell.
    const double* a = nullptr;
};

struct FaceRowOutput {
    double* h;
    double* qn;
    double* qt;
    // predictor_row (required there): the quotients qn / h and qt / h of the values
    // written, for waf_face_row's FaceRowInput::un, ut.
    double* un = nullptr;
    double* ut = nullptr;
};

// Whether a cell of depth h takes part in the fluxes and the pressure stage: at least
// h_dry (h_min) thick and not empty. Non-short-circuit, so that the row kernels using it
// stay vectorised.
[[nodiscard]] inline bool is_wet(double h, double h_dry) noexcept {
    return (h >= h_dry) & (h > 0.0);
}

// The celerity a = sqrt(c h) of a cell as hllc_flux takes it for a face side: a side
// thinner than h_dry (or empty) counts as dry, a = 0. Inline for the row kernels.
[[nodiscard]] inline double side_celerity(double h, double c, double h_dry) noexcept {
    return std::sqrt(c * (is_wet(h, h_dry) ? h : 0.0));
}

// side_celerity of n cells: the values hllc_flux and waf_face_flux take per side.
void celerity_row(const double* h, const double* c, double h_dry, double* a, int n) noexcept;

// First-order HLLC flux, bitwise hllc_flux(ql, qr, c_l, c_r, h_dry), of n faces.
void hllc_face_row(const FaceRowInput& in, const FaceRowOutput& out, int n, double h_dry) noexcept;

// WAF-TVD flux, bitwise waf_face_flux (waf_face.hpp): the limited WAF flux of the HLLC fan, or the
// first-order flux where one of the four stencil cells is thinner than h_dry.
// h_dry must be positive.
void waf_face_row(const FaceRowInput& in, const FaceRowOutput& out, int n, double h_dry,
                  double dt_over_dx, Limiter limiter) noexcept;

// The transverse predictor's half step on one row of cells (Wang & Li 2017 eqs. 6-8): out(m) = q(m)
// - ratio (F(m + off) - F(m)) for n cells, where F(m) is the flux of the face before cell m; a cell
// left with h <= 0 is set empty (predicted states only feed fluxes), and a cell at least h_dry
// thick whose prediction falls below h_dry keeps its state, so that the faces do not take it
// for dry.
void predictor_row(const FaceRowInput& q, const FaceRowOutput& flux, double ratio, double h_dry,
                   const FaceRowOutput& out, int n) noexcept;

}  // namespace avalanche
