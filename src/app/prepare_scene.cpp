#include <algorithm>
#include <sstream>

#include "avalanche/app/prepare_dem.hpp"
#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/core/error.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/release.hpp"

namespace avalanche {

namespace {

PreparedScene prepare_chute_scene(const Scenario& s) {
    const auto& chute = std::get<ChuteGeometry>(s.terrain);
    const auto* shape = std::get_if<ReleaseShape>(&s.release);
    const std::string where = s.source.empty() ? "" : s.source + ": ";
    if (!shape)
        throw ConfigError(where + "release",
                          "the chute frame takes an analytic shape (cap, paraboloid or box)");
    PreparedScene p;
    p.frame = Frame::chute;
    p.grid = chute_grid(chute, s.cell_size);
    p.terrain = chute_terrain(chute, p.grid, s.numerics.gravity);
    p.initial_box.emplace();
    p.initial = state_at_rest(p.grid, rasterize_release(*shape, p.grid), p.terrain, release_cells(*shape, p.grid),
                              &*p.initial_box);
    if (total_volume(p.initial, p.grid, *p.initial_box) <= 0.0)
        throw ConfigError(where + "release", "the release shape does not overlap the chute [0, " +
                                                 std::to_string(chute.length) + "] x [0, " +
                                                 std::to_string(chute.width) + "] m");
    // x along the chute, y across; row 0 of the outputs is the edge at y = width.
    p.geotransform = {p.grid.x0, p.grid.dx, 0.0, p.grid.y_max(), 0.0, -p.grid.dy};
    p.horizontal_position = [chute, grid = p.grid](int i, int j) {
        return std::array<double, 2>{chute.horizontal_distance(grid.x_center(i)), grid.y_center(j)};
    };
    p.cell_area_m2 = p.grid.cell_area();
    std::ostringstream d;
    d << "chute " << chute.length << " x " << chute.width << " m, " << p.grid.nx << " x "
      << p.grid.ny << " cells of " << s.cell_size << " m";
    p.description = d.str();
    return p;
}

}  // namespace

State PreparedScene::initial_copy() const {
    if (!initial_box) return initial;
    State copy(grid);
    const ActiveBox& b = *initial_box;
    const auto width = static_cast<std::size_t>(std::max(b.i1 - b.i0, 0));
    for (int j = b.j0; j < b.j1; ++j)
        for (const auto field : {&State::h, &State::hu, &State::hv})
            std::copy_n((initial.*field).row(j) + b.i0, width, (copy.*field).row(j) + b.i0);
    return copy;
}

PreparedScene prepare_scene(const Scenario& s) {
    if (std::holds_alternative<DemTerrainSpec>(s.terrain)) return prepare_dem_scene(s);
    return prepare_chute_scene(s);
}

}  // namespace avalanche
