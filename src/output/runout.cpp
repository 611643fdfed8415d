#include "avalanche/output/runout.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace avalanche {

ReleaseTop release_top(const Grid& grid, const TerrainFields& terrain, const State& initial,
                       double h_threshold) {
    return release_top(grid, terrain, initial, h_threshold, ActiveBox{0, grid.nx, 0, grid.ny});
}

ReleaseTop release_top(const Grid& grid, const TerrainFields& terrain, const State& initial,
                       double h_threshold, const ActiveBox& holding) {
    ReleaseTop top;
    double top_z = -1e300;
    // Released cells only (their terrain is made, terrain.hpp), in row order.
    const ActiveBox b = holding.clipped(grid.nx, grid.ny);
    for (int j = b.j0; j < b.j1; ++j)
        for (int i = b.i0; i < b.i1; ++i)
            if (initial.h(i, j) > 0.0 && initial.h(i, j) * terrain.normal_thickness(i, j) >= h_threshold &&
                terrain.elevation(i, j) > top_z) {
                top_z = terrain.elevation(i, j);
                top = {i, j};
            }
    return top;
}

RunoutMetrics compute_runout(const Grid& grid, const TerrainFields& terrain, const State& initial,
                             const HazardMaps& maps, const OutputParams& params,
                             const HorizontalPosition& position, double cell_area_m2) {
    return compute_runout(grid, terrain, release_top(grid, terrain, initial, params.h_threshold),
                          maps, params, position, cell_area_m2);
}

RunoutMetrics compute_runout(const Grid& grid, const TerrainFields& terrain, ReleaseTop release,
                             const HazardMaps& maps, const OutputParams& params,
                             const HorizontalPosition& position, double cell_area_m2) {
    RunoutMetrics m;
    const double thr = params.h_threshold;
    const int top_i = release.i, top_j = release.j;
    const double top_z = top_i >= 0 ? terrain.elevation(top_i, top_j) : -1e300;
    std::size_t reached = 0;
    double far2 = -1.0;
    int tip_i = -1, tip_j = -1;
    const std::array<double, 2> top = top_i >= 0 ? position(top_i, top_j) : std::array<double, 2>{0, 0};
    // Outside the maps' reach box every map is zero: nothing to add, no maximum, not
    // reached. Inside it the cells come in the same order as over the whole grid, so the
    // sums and the first farthest cell are the same.
    for_each_cell(maps.reach_box(), grid.nx, [&](int i, int j, std::size_t k) {
        m.max_depth_m = std::max(m.max_depth_m, maps.max_depth()[k]);
        m.max_velocity_ms = std::max(m.max_velocity_ms, maps.max_speed()[k]);
        m.max_pressure_kpa = std::max(m.max_pressure_kpa, maps.max_pressure(k));
        // Only cells with a deposit: the flow reached them, so their terrain is made
        // (terrain.hpp); elsewhere the term was 0 / normal_thickness = 0.
        if (maps.deposit_depth()[k] != 0.0)
            m.deposit_volume_m3 += maps.deposit_depth()[k] / terrain.normal_thickness(i, j) * cell_area_m2;
        if (maps.max_depth()[k] < thr) return;
        ++reached;
        if (top_i < 0) return;
        const auto p = position(i, j);
        const double d2 = (p[0] - top[0]) * (p[0] - top[0]) + (p[1] - top[1]) * (p[1] - top[1]);
        if (d2 > far2) {
            far2 = d2;
            tip_i = i;
            tip_j = j;
        }
    });
    m.affected_area_m2 = static_cast<double>(reached) * cell_area_m2;
    if (top_i < 0 || tip_i < 0) return m;
    m.top_xy = top;
    m.tip_xy = position(tip_i, tip_j);
    m.runout_length_m = std::sqrt(far2);
    m.fall_height_m = top_z - terrain.elevation(tip_i, tip_j);
    if (m.runout_length_m > 0.0) {
        m.travel_angle_deg = std::atan2(m.fall_height_m, m.runout_length_m) * 180.0 / std::numbers::pi;
        if (m.fall_height_m > 0.0) m.runout_efficiency = m.runout_length_m / m.fall_height_m;
    }
    return m;
}

}  // namespace avalanche
