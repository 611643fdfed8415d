#pragma once
// Earth pressure coefficients of the Savage–Hutter theory (Savage & Hutter 1989;
// Wang & Li 2017 eqs. 2-3):
//   k_x(act/pass) = 2 (1 -/+ sqrt(1 - cos^2 phi (1 + tan^2 delta))) / cos^2 phi - 1
//   k_y(act/pass) = 1/2 (1 + k_x -/+ sqrt((1 - k_x)^2 + 4 tan^2 delta))
// Active where the flow extends (du/dx > 0), passive where it compresses; k_y is
// evaluated with the k_x chosen in the same cell. On the grid: passive where the central
// difference is negative, confirmed at a second scale; active where it is not negative;
// otherwise the cell keeps its regime (numerics/regime_rows.cpp, next_regime).
#include "avalanche/physics/material.hpp"

namespace avalanche {

struct EarthPressureCoefficients {
    double kx_active = 1.0, kx_passive = 1.0;
    // k_y indexed by the k_x regime of the cell: [kx regime][ky regime]
    double ky_given_kx_active_active = 1.0, ky_given_kx_active_passive = 1.0;
    double ky_given_kx_passive_active = 1.0, ky_given_kx_passive_passive = 1.0;

    [[nodiscard]] double kx(bool x_active) const { return x_active ? kx_active : kx_passive; }
    [[nodiscard]] double ky(bool x_active, bool y_active) const {
        if (x_active) return y_active ? ky_given_kx_active_active : ky_given_kx_active_passive;
        return y_active ? ky_given_kx_passive_active : ky_given_kx_passive_passive;
    }
};

// k_x for the given regime; requires 0 <= delta <= phi < 90 deg (checked by validate()).
double earth_pressure_kx(double phi_rad, double delta_rad, bool active);
// k_y for the given regime and the cell's k_x.
double earth_pressure_ky(double kx, double delta_rad, bool active);

// All six coefficients, or all ones for the isotropic model.
EarthPressureCoefficients earth_pressure_coefficients(const MaterialParams& m);

}  // namespace avalanche
