#pragma once
// A rough valley DEM for the tests that compare runs to the bit
// (test_terrain_on_demand.cpp, test_active_bands.cpp; support/same_bits.hpp compares).
#include <cmath>
#include <vector>

#include "avalanche/core/field.hpp"
#include "avalanche/core/grid.hpp"

namespace avalanche::testing {

// A valley falling towards +y with `slope` (elevation drop per metre), its floor along the
// middle column (`across`: the cross-profile's curvature), and a rough surface, so that
// every cell has curvature.
inline std::vector<double> rough_valley(const Grid& g, double slope, double across) {
    std::vector<double> z(g.cells());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const double x = g.x_center(i), y = g.y_center(j);
            const double side = across * (x - 0.5 * g.x_max()) * (x - 0.5 * g.x_max());
            const double rough = 0.3 * std::sin(0.37 * i + 0.11 * j * j) * std::cos(0.23 * j + 0.05 * i * i);
            z[static_cast<std::size_t>(j) * g.nx + i] = slope * (g.y_max() - y) + side + rough;
        }
    return z;
}

}  // namespace avalanche::testing
