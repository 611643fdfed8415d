#include "avalanche/physics/terrain.hpp"

#include "avalanche/core/state.hpp"

namespace avalanche {

void TerrainFields::allocate(const Grid& g, bool curvature, bool metric) {
    const auto make = [&](double v) { return Field2D(g.nx, g.ny, kGhostLayers, v); };
    ax = make(0.0);
    ay = make(0.0);
    px = make(0.0);
    py = make(0.0);
    gn = make(0.0);
    normal_thickness = make(1.0);
    elevation = make(0.0);
    has_curvature = curvature;
    has_metric = metric;
    cxx = curvature ? make(0.0) : Field2D();
    cxy = curvature ? make(0.0) : Field2D();
    cyy = curvature ? make(0.0) : Field2D();
    sx = metric ? make(0.0) : Field2D();
    sy = metric ? make(0.0) : Field2D();
}

void TerrainFields::extend_to_ghosts() {
    for (Field2D* f : {&ax, &ay, &px, &py, &gn, &cxx, &cxy, &cyy, &sx, &sy, &normal_thickness, &elevation})
        if (!f->empty()) f->extend_to_ghosts();
}

}  // namespace avalanche
