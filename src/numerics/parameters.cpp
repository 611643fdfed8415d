#include "avalanche/numerics/parameters.hpp"

#include <cmath>
#include <string>

#include "avalanche/core/error.hpp"

namespace avalanche {

void validate(const NumericsParams& n) {
    if (!std::isfinite(n.cfl) || n.cfl <= 0.0 || n.cfl > 0.5)
        throw ConfigError("numerics.cfl", "expected a Courant number in (0, 0.5] (Wang & Li 2017 eq. 11), got " +
                                              std::to_string(n.cfl));
    if (!std::isfinite(n.h_min) || n.h_min < 0.0)
        throw ConfigError("numerics.h_min", "expected a thin-layer depth >= 0 m (0 = automatic)");
    if (!std::isfinite(n.h_min_relative) || n.h_min_relative <= 0.0 || n.h_min_relative >= 1.0)
        throw ConfigError("numerics.h_min_relative", "expected a fraction in (0, 1)");
    if (n.source_substeps < 1 || n.source_substeps > 1000)
        throw ConfigError("numerics.source_substeps", "expected an integer in [1, 1000]");
    if (!std::isfinite(n.t_end) || n.t_end <= 0.0)
        throw ConfigError("numerics.t_end", "expected a positive end time in seconds");
    if (!std::isfinite(n.output_interval) || n.output_interval <= 0.0)
        throw ConfigError("numerics.output_interval", "expected a positive interval in seconds");
    if (!std::isfinite(n.stop_ke_fraction) || n.stop_ke_fraction < 0.0 || n.stop_ke_fraction >= 1.0)
        throw ConfigError("numerics.stop_ke_fraction", "expected a fraction in [0, 1)");
    if (!std::isfinite(n.stop_duration) || n.stop_duration < 0.0)
        throw ConfigError("numerics.stop_duration", "expected a duration >= 0 s");
    if (n.active_margin < 3)
        throw ConfigError("numerics.active_margin", "expected at least 3 cells");
    if (!std::isfinite(n.gravity) || n.gravity <= 0.0)
        throw ConfigError("numerics.gravity", "expected a positive gravity in m/s^2");
}

double advection_courant(const NumericsParams& n) {
    return n.splitting == Splitting::lsl ? 0.5 * n.cfl : n.cfl;
}

}  // namespace avalanche
