#pragma once
// The Savage-Hutter regime rule (active or passive earth pressure per direction) on
// the rows of a grid, for the vector units like the other row kernels
// (cell_rows.hpp). The rule, stated in regime_row below, compares the velocities of a
// cell's neighbours one and two cells away in each direction. What it needs of a single
// cell (wet or not, within the rest speed or not) is computed once per grid row
// (regime_terms_row) and read by the five regime rows around it: computed per
// difference, as until 2026-12-03, it was computed ten times per cell, and the regimes
// took 12-24 % of a run on benchmark (a) (docs/performance.md).
// Pointers address column 0 of their row; cells i0 .. i1 - 1 are processed.
#include <cstdint>

namespace avalanche {

// The Savage-Hutter regime of a cell, carried from advection to advection (Stepper,
// regime_row): bit kRegimeXActive set where k_x is active, bit kRegimeYActive where
// k_y is. A cell starts, and a dry or thin cell restarts, with both active
// (kRegimeAtStart). Four bytes, not one: with one-byte flags GCC 12 left the AVX-512F
// clone of regime_row scalar (no 64-lane byte vectors without AVX-512BW), and the
// x86-64-v4 clones, which have them, vectorise none of its block loops either.
using RegimeFlags = std::int32_t;
inline constexpr RegimeFlags kRegimeXActive = 1, kRegimeYActive = 2;
inline constexpr RegimeFlags kRegimeAtStart = kRegimeXActive | kRegimeYActive;
// The form in which the stepper keeps a grid's regimes (Stepper::regime_): one byte per
// cell, the flags XOR kRegimeAtStart, so that a cell at start holds 0 and a grid's
// flags are made without writing them (field_storage.hpp). The kernels work on rows of
// RegimeFlags; a row is converted as the regime stage reads and stores it. (In four
// bytes, the stage's first read of a row of the grid's regimes took 2 % of case (a).)
using StoredRegime = std::uint8_t;
constexpr StoredRegime stored_regime(RegimeFlags f) {
    return static_cast<StoredRegime>(f ^ kRegimeAtStart);
}
constexpr RegimeFlags regime_of_stored(StoredRegime b) {
    return static_cast<RegimeFlags>(b) ^ kRegimeAtStart;
}

// Rows the regime stage reads: the state (depth and momenta) of row r, and the depth
// and y-momentum of the rows one (s, n) and two (ss, nn) below and above it; in the DEM
// frame the surface gradient s_x of row r and s_y of the five rows (null in bed-fitted
// frames: all or none).
struct RegimeRowInput {
    const double *h, *hu, *hv;
    const double *h_s, *hv_s, *h_n, *hv_n;
    const double *h_ss, *hv_ss, *h_nn, *hv_nn;
    const double *sx = nullptr, *sy = nullptr;
    const double *sy_s = nullptr, *sy_n = nullptr, *sy_ss = nullptr, *sy_nn = nullptr;
    // Confirm a compression at both scales, not at either: the first-order scheme's
    // rule (regime_rows.cpp, next_regime, says why).
    bool confirm_at_both_scales = false;
};

// Updates the regime of cells i0 .. i1 - 1 of one row in place (regime_rows.cpp,
// next_regime): passive where the central velocity difference is negative and a second
// scale confirms it (both one-sided differences negative, or the difference over four
// cells; both of these with in.confirm_at_both_scales, the first-order scheme's rule);
// active where the central difference is not negative; otherwise (a central
// compression that is not confirmed) the cell keeps the regime it had. Two velocities
// whose along-surface components are both at most rest_speed count as equal (their
// difference vanishes, so it extends): the stepper passes tan(delta) g tau / 2, below
// which a velocity is the splitting's residue in a deposit at rest (docs/numerics.md,
// advection step 2). A difference with a thin or dry cell (h < h_min) extends: such a
// cell has no velocity of its own. Each cell reads only its own previous regime,
// so rows may be updated in any order and by any thread. The x-differences are clamped
// to the columns lo and hi. Pointers address column 0.
// This is regime_terms_row on the five rows and regime_row_from_terms, with scratch
// rows of its own; the stepper calls those two itself and keeps each row's terms for
// the five regime rows that read them.
void regime_row(const RegimeRowInput& in, RegimeFlags* regime, double h_min, double rest_speed,
                int i0, int i1, int lo, int hi) noexcept;

// What the rule needs of each cell of a row, 1.0 or 0.0 per cell: whether it is wet
// (h >= h_min, h > 0), and per direction whether it is wet and its along-surface
// velocity component, |hu / h| sqrt(1 + s_x^2) or |hv / h| sqrt(1 + s_y^2), is at most
// the rest speed ("still").
struct RegimeTermsRow {
    double* wet;
    double* still_x;
    double* still_y;
    // Where not null, the row's velocity quotients too, u = hu / h and v = hv / h, the
    // values of state_velocity_row (cell_rows.hpp): the stepper computes both from one
    // read of the state rows (advection.cpp, regime_row_into).
    double* u = nullptr;
    double* v = nullptr;
};

// sx, sy: the row's surface gradients in the DEM frame, null in bed-fitted frames.
void regime_terms_row(const double* h, const double* hu, const double* hv, const double* sx,
                      const double* sy, double h_min, double rest_speed, const RegimeTermsRow& out,
                      int i0, int i1) noexcept;

// The terms the rule reads around row r (regime_terms_row): of the rows r, s, n, ss, nn
// (the rows of RegimeRowInput), still_x of row r only.
struct RegimeRowTerms {
    const double *wet, *wet_s, *wet_n, *wet_ss, *wet_nn;
    const double* still_x;
    const double *still_y, *still_y_s, *still_y_n, *still_y_ss, *still_y_nn;
};

// regime_row from the terms of the rows (the depth and momenta of RegimeRowInput; its
// gradients are in the terms).
void regime_row_from_terms(const RegimeRowInput& in, const RegimeRowTerms& t,
                           RegimeFlags* regime, int i0, int i1, int lo, int hi) noexcept;

}  // namespace avalanche
