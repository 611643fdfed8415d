#pragma once
// Per-cell kernels of one grid row, written for the vector units like the face
// kernels (face_flux_rows.hpp): the point-wise sources and the CFL rate. Each is the
// stepper's scalar loop body with its branches turned into selections, so the results
// are bitwise those of the scalar code (tests/regression/test_cell_rows.cpp).
// Pointers address element 0 of the row; cells i0 .. i1 - 1 are processed.

namespace avalanche {

// Terrain rows the sources read; curvature and metric rows are null when the
// terrain has none.
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

// max over the wet cells (h >= h_min, h > 0) of the row of
//   (|u| + sqrt(kx px h)) / dx and (|v| + sqrt(ky py h)) / dy, or 0.
double cfl_rate_row(const double* h, const double* hu, const double* hv, const double* px,
                    const double* py, double kx, double ky, double dx, double dy, double h_min,
                    int i0, int i1) noexcept;

}  // namespace avalanche
