#pragma once
// Run metrics of MODEL.md section 5: runout length, fall height, travel angle,
// runout efficiency and affected area.
//
// Definitions (docs/products.md):
//  - top: the release cell (initial bed-normal depth >= h_thr) with the highest bed;
//  - tip: the reached cell (max depth >= h_thr) farthest, horizontally, from the top;
//  - runout length L: horizontal distance top -> tip (m);
//  - fall height H: bed elevation of the top minus that of the tip (m);
//  - travel angle alpha = atan(H / L) (the Heim angle, deg);
//  - runout efficiency = L / H (Wang & Li 2017 section 2.3: runout over height);
//  - affected area: number of reached cells x the horizontal cell area (m^2).
#include <array>
#include <functional>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/output/hazard_maps.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

struct RunoutMetrics {
    double runout_length_m = 0.0;
    double fall_height_m = 0.0;
    double travel_angle_deg = 0.0;
    double runout_efficiency = 0.0;
    double affected_area_m2 = 0.0;
    double deposit_volume_m3 = 0.0;   // material thicker than h_thr at the end
    double max_depth_m = 0.0;
    double max_velocity_ms = 0.0;
    double max_pressure_kpa = 0.0;
    std::array<double, 2> top_xy{0, 0}, tip_xy{0, 0};  // horizontal positions (m)
};

// Horizontal (map) position of a cell centre: the grid coordinates in the DEM frame;
// in the chute frame the horizontal distance along the bed and y.
using HorizontalPosition = std::function<std::array<double, 2>(int i, int j)>;

// The top of the release: the cell with initial bed-normal depth >= h_threshold with the
// highest bed (the first in row order among equals); i = j = -1 without one. All the
// runout metrics need of the initial state, so a run can hand its state to the solver
// and keep only this.
struct ReleaseTop {
    int i = -1, j = -1;
};
ReleaseTop release_top(const Grid& grid, const TerrainFields& terrain, const State& initial,
                       double h_threshold);
// The same, reading only the cells of `holding`, which holds every cell with material.
ReleaseTop release_top(const Grid& grid, const TerrainFields& terrain, const State& initial,
                       double h_threshold, const ActiveBox& holding);

// cell_area_m2: horizontal area of a cell (the DEM frame's dx dy; in the chute
// frame the bed area is used, as the chute has no map projection).
RunoutMetrics compute_runout(const Grid& grid, const TerrainFields& terrain, ReleaseTop top,
                             const HazardMaps& maps, const OutputParams& params,
                             const HorizontalPosition& position, double cell_area_m2);
// The same from the initial state (release_top with params.h_threshold).
RunoutMetrics compute_runout(const Grid& grid, const TerrainFields& terrain, const State& initial,
                             const HazardMaps& maps, const OutputParams& params,
                             const HorizontalPosition& position, double cell_area_m2);

}  // namespace avalanche
