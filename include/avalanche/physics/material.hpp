#pragma once
// Material parameters of the Savage–Hutter model. Degrees only at this boundary;
// the solver works with radians and tangents.
#include <cmath>
#include <numbers>

namespace avalanche {

enum class EarthPressureModel {
    savage_hutter,  // active/passive k_x, k_y of Wang & Li (2017) eqs. 2-3
    isotropic,      // k = 1: hydrostatic, shallow-water-like
};

struct MaterialParams {
    double phi_deg = 35.0;    // internal friction angle (deg), 0 < phi < 90
    double delta_deg = 20.0;  // basal (bed) friction angle (deg), 0 <= delta <= phi
    EarthPressureModel earth_pressure = EarthPressureModel::savage_hutter;
    double density = 2000.0;  // bulk density (kg/m^3), used for impact pressure only

    [[nodiscard]] double tan_delta() const { return std::tan(delta_deg * std::numbers::pi / 180.0); }
};

// Throws ConfigError naming the key when a value is outside the theory's range
// (delta > phi makes the earth-pressure square root imaginary).
void validate(const MaterialParams& m);

}  // namespace avalanche
