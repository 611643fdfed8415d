#pragma once
// The chute (bed-fitted) frame of MODEL.md section 3.1 and Wang & Li (2017)
// section 2.3: x runs along the bed from the top of an inclined plane, through an
// optional circular transition, onto a runout of constant inclination; y runs
// across. The inclination zeta(x) is continuous and piecewise linear in x (a
// circular arc in the transition), so the curvature there is constant:
//   kappa = -dzeta/dx = (zeta_plane - zeta_runout) / (x_end - x_start).
#include <optional>

#include "avalanche/core/grid.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

struct ChuteGeometry {
    double slope_deg = 45.0;          // inclination of the upper plane
    double length = 60.0;             // m along the bed
    double width = 40.0;              // m across
    std::optional<double> transition_start;  // m along x; both or neither
    std::optional<double> transition_end;
    double runout_slope_deg = 0.0;    // inclination after the transition

    [[nodiscard]] bool has_transition() const { return transition_start.has_value(); }
    // Inclination (rad) at bed coordinate x.
    [[nodiscard]] double inclination(double x) const;
    // -dzeta/dx at x (1/m), zero outside the transition.
    [[nodiscard]] double curvature(double x) const;
    // Height above the bed point at x = length (m), from dz/dx = -sin(zeta).
    [[nodiscard]] double elevation(double x) const;
    // Horizontal distance from the top (x = 0) to the bed point at x (m).
    [[nodiscard]] double horizontal_distance(double x) const;
};

void validate(const ChuteGeometry& c);

// The grid covering [0, length] x [0, width] with square cells of cell_size.
Grid chute_grid(const ChuteGeometry& c, double cell_size);

// Terrain coefficients of the chute frame (gravity g in m/s^2).
TerrainFields chute_terrain(const ChuteGeometry& c, const Grid& grid, double gravity);

}  // namespace avalanche
