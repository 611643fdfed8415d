#pragma once
// Conserved state U = (h, hu, hv) of the depth-averaged model, structure of arrays.
// h is the thickness the frame's mass balance conserves: bed-normal in the chute
// frame, vertical in the DEM frame (docs/theory.md). hu, hv are the momenta in
// the grid directions.
#include "avalanche/core/field.hpp"
#include "avalanche/core/grid.hpp"

namespace avalanche {

inline constexpr int kGhostLayers = 2;  // WAF limiter needs two cells upwind of a face

struct State {
    Field2D h, hu, hv;

    State() = default;
    explicit State(const Grid& g)
        : h(g.nx, g.ny, kGhostLayers), hu(g.nx, g.ny, kGhostLayers), hv(g.nx, g.ny, kGhostLayers) {}
};

}  // namespace avalanche
