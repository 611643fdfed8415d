#pragma once
// The computational grid: a structured Cartesian mesh of nx x ny cells.
// Solver orientation: i runs along x (columns), j runs along y (rows) with
// j = 0 at the smallest y ("south" in a map, one chute edge in the chute frame).
// Only avalanche_io flips rows to the GeoTIFF "row 0 at the top" convention.
#include <cstddef>

namespace avalanche {

struct Grid {
    int nx = 0;        // cells along x
    int ny = 0;        // cells along y
    double dx = 1.0;   // cell size along x (m)
    double dy = 1.0;   // cell size along y (m)
    double x0 = 0.0;   // x of the west (left) cell edge
    double y0 = 0.0;   // y of the south (bottom) cell edge

    [[nodiscard]] std::size_t cells() const { return static_cast<std::size_t>(nx) * ny; }
    [[nodiscard]] double x_center(int i) const { return x0 + (i + 0.5) * dx; }
    [[nodiscard]] double y_center(int j) const { return y0 + (j + 0.5) * dy; }
    [[nodiscard]] double cell_area() const { return dx * dy; }
    [[nodiscard]] double x_max() const { return x0 + nx * dx; }
    [[nodiscard]] double y_max() const { return y0 + ny * dy; }
};

}  // namespace avalanche
