#pragma once
// Per-cell kernels of one grid row, written for the vector units like the face
// kernels (face_flux_rows.hpp): the point-wise sources, the CFL rate, the advection's
// per-cell stage and the time loop's state scan. Each but the scan is the stepper's
// scalar loop body with its branches turned into selections, so the results are
// bitwise those of the scalar code (tests/regression/test_cell_rows.cpp); the scan
// defines its own order of summation (StateRowScan).
// Pointers address element 0 of the row; cells i0 .. i1 - 1 are processed.
#include <cstdint>
#include <limits>

#include "avalanche/numerics/regime_rows.hpp"
#include "avalanche/physics/earth_pressure.hpp"

namespace avalanche {

// Terrain rows the sources read; curvature and metric rows are null when the
// terrain has none, ax, ay and gn in the DEM frame (see below).
struct SourceRowTerrain {
    const double* ax;
    const double* ay;
    const double* gn;
    const double* elevation;
    const double* cxx;
    const double* cxy;
    const double* cyy;
    const double* sx;
    const double* sy;
    // In the DEM frame (sx, sy set) ax, ay and gn are not read (the terrain does not
    // store them): they are computed from sx, sy with this g
    // (TerrainFields::slope_gravity, dem_coefficients.hpp).
    double slope_gravity = 0.0;
};

struct SourceRowParams {
    double substep;  // dt / m
    int substeps;    // m
    double tan_delta;
    double gravity;        // for the energy cap
    double energy_budget;  // per unit mass; the cap speed^2 is 2 (budget - g z)
};

// Stepper::apply_sources on one row: m sub-steps of tangential gravity and Coulomb
// friction, then the energy cap (stepper.hpp). Dry cells (h <= 0) are left alone.
void apply_sources_row(double* h, double* hu, double* hv, const SourceRowTerrain& t,
                       const SourceRowParams& p, int i0, int i1) noexcept;

// Terrain rows the CFL rate reads: the pressure coefficients px, py, or in the DEM
// frame (sx, sy set; px, py then null) the slopes they are computed from with
// slope_gravity (TerrainFields::slope_gravity, dem_coefficients.hpp).
struct CflRowTerrain {
    const double *px = nullptr, *py = nullptr;
    const double *sx = nullptr, *sy = nullptr;
    double slope_gravity = 0.0;
};

// max over the wet cells (h >= h_min, h > 0) of the row of
//   (|u| + sqrt(kx px h)) / dx and (|v| + sqrt(ky py h)) / dy, or 0.
double cfl_rate_row(const double* h, const double* hu, const double* hv, const CflRowTerrain& t,
                    double kx, double ky, double dx, double dy, double h_min, int i0,
                    int i1) noexcept;

// What the time loop's scan (scan_state, simulation.hpp) needs of cells i0 .. i1 - 1 of
// one row of the state.
struct StateRowScan {
    // Twice the kinetic energy per unit area summed over the cells with h > 0:
    // sum of (hu^2 + hv^2) / h, in double, the cells i0 + 8 k + l added into partial
    // sum l in order of k, the eight partial sums then added in order of l: the same bits
    // on every instruction set and thread count. (Summed in long double cell by cell
    // before, a scalar x87 division and addition per cell, ~3 ns of a 44 ns update;
    // docs/performance.md.) Meaningless when first_bad >= 0.
    double twice_kinetic = 0.0;
    int first_bad = -1;   // the first cell with a non-finite value or h < 0, or -1
    bool moving = false;  // some hu or hv of the row not exactly zero
};

StateRowScan state_scan_row(const double* h, const double* hu, const double* hv, int i0,
                            int i1) noexcept;

// Rows the pressure stage reads: the state's depth and velocity quotients of row r
// (u = hu / h, v = hv / h of every cell, as state_velocity_row computes them), the
// terrain's row r (sx, sy null in bed-fitted frames) and the row's regime
// (regime_row), required unless the pressure is isotropic.
// In the DEM frame (sx, sy set) px, py, gn and nt are not read (null; the terrain
// stores none but nt): they are computed from sx, sy with slope_gravity
// (TerrainFields::slope_gravity, dem_coefficients.hpp).
struct PressureRowInput {
    const double *h, *u, *v;
    const double *px, *py, *gn, *nt, *sx, *sy;
    const RegimeFlags* regime = nullptr;
    double slope_gravity = 0.0;
};

// The invariant bounds of a dry or thin cell, which bounds nothing: u_lo = v_lo =
// kNoVelocityBound, u_hi = v_hi = -kNoVelocityBound.
inline constexpr double kNoVelocityBound = std::numeric_limits<double>::max();

// Per cell: the pressure coefficients k p and the invariant bounds of the update.
struct PressureRowOutput {
    double *cx, *cy, *u_lo, *u_hi, *v_lo, *v_hi, *speed_hi;
    // The celerities sqrt(cx h), sqrt(cy h) of cells at least h_min thick, 0 on the
    // others: celerity_row's values (face_flux_rows.hpp) for the first-order faces on
    // this state, taken from the bounds' square roots.
    double *ax, *ay;
};

struct PressureRowParams {
    EarthPressureCoefficients k;
    double k_max;  // largest coefficient, for the along-surface speed bound
    double h_min;
    bool isotropic;
};

// The advection's per-cell stage on cells i0 .. i1 - 1 of one row (advection.cpp,
// Stepper::pressure_row: the pressure coefficients of the cell's regime (regime_row);
// Riemann-invariant bounds u -/+ 2a, v -/+ 2a and the along-surface speed bound of wet
// cells). Output pointers address column 0 like the inputs.
void pressure_row(const PressureRowInput& in, const PressureRowOutput& out,
                  const PressureRowParams& p, int i0, int i1) noexcept;

// The velocity quotients of one cell, with one division for both: state_velocity_row's
// expression, which the regime terms' kernel shares (regime_terms_row) so that the two
// give the same bits.
struct VelocityQuotients {
    double u, v;
};
[[nodiscard]] inline VelocityQuotients velocity_quotients(double h, double hu, double hv) noexcept {
    const double inv = 1.0 / h;
    return {hu * inv, hv * inv};
}

// The velocity quotients u = hu / h and v = hv / h of cells i0 .. i1 - 1 of a row,
// for every cell (a dry cell's are inf or NaN; the kernels mask them): computed once
// per cell for the pressure stage and the first-order fluxes, the same quotients
// those computed per face.
void state_velocity_row(const double* h, const double* hu, const double* hv, double* u, double* v,
                        int i0, int i1) noexcept;

}  // namespace avalanche
