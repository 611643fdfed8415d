#pragma once
// Parameters of the hazard products (MODEL.md section 5), with units and defaults in
// one place (STYLE.md 5). No I/O here: the writers read these, the scenario sets them.
#include <cmath>

#include "avalanche/core/error.hpp"

namespace avalanche {

struct OutputParams {
    // Depth threshold h_thr (m, bed-normal) of the hazard maps: a cell is "reached"
    // (arrival time, affected area) once h >= h_thr. 1 cm ignores the thin-layer film.
    double h_threshold = 0.01;
    // Impact-pressure class limits (kPa); 30 and 3 kPa are the Swiss avalanche zoning
    // limits between high/medium and medium/low intensity.
    double pressure_high_kpa = 30.0;
    double pressure_low_kpa = 3.0;
};

// Throws ConfigError naming the key for a value the products cannot use.
inline void validate(const OutputParams& o) {
    if (!std::isfinite(o.h_threshold) || o.h_threshold <= 0.0)
        throw ConfigError("output.h_threshold", "expected a positive depth threshold in metres");
    if (!std::isfinite(o.pressure_low_kpa) || o.pressure_low_kpa <= 0.0)
        throw ConfigError("output.pressure_low_kpa", "expected a positive pressure in kPa");
    if (!std::isfinite(o.pressure_high_kpa) || o.pressure_high_kpa <= o.pressure_low_kpa)
        throw ConfigError("output.pressure_high_kpa",
                          "expected a pressure in kPa above output.pressure_low_kpa");
}

}  // namespace avalanche
