#pragma once
// The scenes of the benchmarks (docs/performance.md): each holds everything a
// Simulation needs, built through the public API exactly as the tool builds them.
// A Scene must outlive its Simulation (the Stepper keeps a reference to the terrain).
#include <string>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/physics/material.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche::bench {

struct Scene {
    std::string name;
    Grid grid;
    TerrainFields terrain;
    MaterialParams material;
    NumericsParams numerics;
    State initial;
    ActiveBox released;  // holds every cell of initial with material (state_at_rest)
    double h_min = 0.0;
    // Of the scene's making, the seconds its DEM's elevations took to sample from their
    // function: the benchmark's stand-in for reading a DEM file, which a run of the tool
    // does with GDAL instead (0 for the chute, whose terrain is analytic).
    double dem_seconds = 0.0;
};

// (a) Tilted-plane DEM of n x n cells of cell_size m falling along +x at slope_deg,
// wet everywhere with a uniform bed-normal layer of thickness m (delta 20 < slope: it flows).
Scene tilted_plane(int n, double cell_size, double slope_deg, double thickness, Scheme scheme);

// (b) The paper's parametric chute (Wang & Li 2017 section 3): 45 deg plane 60 x 40 m,
// transition 25-30 m to a horizontal runout, cap r = 2.5 m at (7.5, 20), phi 35,
// delta 20, cells of cell_size m, t_end 60 s (it stops long before).
Scene paper_chute(double cell_size, Scheme scheme);

// The synthetic valley DEM (metres), defined everywhere so that any crop of it is
// the same terrain: a parabolic cross-section around x = 0 (linear beyond 1.5 km,
// C1), plus a concave profile along y rising from a flat floor (y <= 0) to 3 km at
// y = 10 km (28 deg at 9 km; linear beyond).
double valley_elevation(double x, double y);

// A valley scene: nx x ny cells of cell_size m with south-west corner (x0, y0),
// a paraboloid release of radius and thickness at (xc, yc); delta 12.5, phi 25.
struct ValleyRelease {
    double xc = 0.0, yc = 9000.0;
    double radius = 200.0, thickness = 20.0;
};
Scene valley(int nx, int ny, double cell_size, double x0, double y0, const ValleyRelease& release,
             Scheme scheme, double t_end);

std::string to_string(Scheme s);

}  // namespace avalanche::bench
