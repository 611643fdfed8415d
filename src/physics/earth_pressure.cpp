#include "avalanche/physics/earth_pressure.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "avalanche/core/error.hpp"

namespace avalanche {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
}

double earth_pressure_kx(double phi_rad, double delta_rad, bool active) {
    const double c2 = std::cos(phi_rad) * std::cos(phi_rad);
    const double t2 = std::tan(delta_rad) * std::tan(delta_rad);
    // 1 - cos^2 phi / cos^2 delta >= 0 for delta <= phi; round-off at delta == phi
    // can make it -1e-17, which must not become NaN.
    const double root = std::sqrt(std::max(0.0, 1.0 - c2 * (1.0 + t2)));
    return 2.0 * (1.0 + (active ? -root : root)) / c2 - 1.0;
}

double earth_pressure_ky(double kx, double delta_rad, bool active) {
    const double t2 = std::tan(delta_rad) * std::tan(delta_rad);
    const double root = std::sqrt((1.0 - kx) * (1.0 - kx) + 4.0 * t2);
    return 0.5 * (1.0 + kx + (active ? -root : root));
}

EarthPressureCoefficients earth_pressure_coefficients(const MaterialParams& m) {
    EarthPressureCoefficients k;
    if (m.earth_pressure == EarthPressureModel::isotropic) return k;
    const double phi = m.phi_deg * kDeg, delta = m.delta_deg * kDeg;
    k.kx_active = earth_pressure_kx(phi, delta, true);
    k.kx_passive = earth_pressure_kx(phi, delta, false);
    k.ky_given_kx_active_active = earth_pressure_ky(k.kx_active, delta, true);
    k.ky_given_kx_active_passive = earth_pressure_ky(k.kx_active, delta, false);
    k.ky_given_kx_passive_active = earth_pressure_ky(k.kx_passive, delta, true);
    k.ky_given_kx_passive_passive = earth_pressure_ky(k.kx_passive, delta, false);
    return k;
}

void validate(const MaterialParams& m) {
    if (!std::isfinite(m.phi_deg) || m.phi_deg <= 0.0 || m.phi_deg >= 90.0)
        throw ConfigError("material.phi_deg", "expected an internal friction angle in (0, 90) degrees, got " +
                                                  std::to_string(m.phi_deg));
    if (!std::isfinite(m.delta_deg) || m.delta_deg < 0.0 || m.delta_deg >= 90.0)
        throw ConfigError("material.delta_deg", "expected a bed friction angle in [0, 90) degrees, got " +
                                                    std::to_string(m.delta_deg));
    if (m.earth_pressure == EarthPressureModel::savage_hutter && m.delta_deg > m.phi_deg)
        throw ConfigError("material.delta_deg",
                          "bed friction angle " + std::to_string(m.delta_deg) +
                              " exceeds the internal friction angle phi_deg = " + std::to_string(m.phi_deg) +
                              "; Savage-Hutter earth pressure requires delta <= phi (or earth_pressure = "
                              "\"isotropic\")");
    if (!std::isfinite(m.density) || m.density <= 0.0)
        throw ConfigError("material.density", "expected a positive bulk density in kg/m^3");
}

}  // namespace avalanche
