#pragma once
// Analytic release shapes of the scenario files, as bed-normal thickness.
// Cell values are cell averages (sub-sampled), so the released volume converges
// to the shape's exact volume at second order in the cell size.
#include <array>
#include <variant>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

struct CapRelease {         // hemispherical cap h = sqrt(R^2 - r^2)
    std::array<double, 2> center{7.5, 20.0};
    double radius = 2.5;
};
struct ParaboloidRelease {  // h = thickness (1 - r^2 / R^2)
    std::array<double, 2> center{7.5, 20.0};
    double radius = 2.5;
    double thickness = 1.0;
};
struct BoxRelease {         // uniform thickness on [x1, x2] x [y1, y2]
    std::array<double, 2> x{0.0, 1.0};
    std::array<double, 2> y{0.0, 1.0};
    double thickness = 1.0;
};
using ReleaseShape = std::variant<CapRelease, ParaboloidRelease, BoxRelease>;

void validate(const ReleaseShape& r);

// Bed-normal thickness of the shape at a point.
double release_thickness_at(const ReleaseShape& r, double x, double y);

// Cell-averaged bed-normal thickness on the grid (interior cells, ghosts zero).
Field2D rasterize_release(const ReleaseShape& r, const Grid& grid, int subsamples = 8);
// The cells over the shape's extent: rasterize_release's field is zero outside them.
ActiveBox release_cells(const ReleaseShape& r, const Grid& grid);

// Initial state at rest from a bed-normal thickness field: h = thickness / normal_thickness.
// With `released`, also the bounding box of the released cells: every cell of the state
// outside it is zero (empty when nothing is released).
State state_at_rest(const Grid& grid, const Field2D& normal_thickness_of_release,
                    const TerrainFields& terrain, ActiveBox* released = nullptr);
// The same where the thickness is zero outside `within` (release_cells of the shape it
// was rasterised from), read only inside it.
State state_at_rest(const Grid& grid, const Field2D& normal_thickness_of_release,
                    const TerrainFields& terrain, const ActiveBox& within, ActiveBox* released = nullptr);

}  // namespace avalanche
