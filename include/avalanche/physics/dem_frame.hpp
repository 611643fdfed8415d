#pragma once
// The DEM frame of MODEL.md section 3.2: a horizontal projected grid over a bed
// z_b(x, y) of any steepness, in the slope-consistent form derived in
// docs/theory.md ("DEM frame"). In short, with s^2 = 1 + |grad z|^2 = 1/cos^2(theta):
//   state        h = vertical thickness (volume per horizontal area), (u, v) = horizontal
//                velocity, so mass is conserved exactly on the projected grid;
//   gravity      a = -g grad z / s^2          (Hergarten & Robl 2015: the along-surface
//                                              gravity, projected on the horizontal);
//   pressure     p_x = g / (s^2 (1 + z_x^2)),  p_y = g / (s^2 (1 + z_y^2))
//                (exact for slopes aligned with a grid axis: g cos^4 along the fall
//                line, g cos^2 across it);
//   friction     load N = g / s + (z_xx u^2 + 2 z_xy u v + z_yy v^2) / s, against the
//                true speed |(u, v, z_x u + z_y v)|;
//   output       bed-normal thickness = h / s.
// On a uniform plane this is the chute frame written in projected coordinates
// (x_h = x cos(theta), h_vert = h / cos(theta), u_h = u cos(theta)), so the two
// frames give the same solution (tests/verification/test_dem_frame.cpp).
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

struct DemFrameOptions {
    // Curvatures below this (1/m) count as zero, so that planar terrain skips the
    // centripetal term (round-off of second differences on a plane is ~1e-13 z/dx^2).
    double curvature_tolerance = 1e-9;
    // Smooth the curvature with a 3x3 mean: the second differences of a DEM amplify
    // its noise by 1/dx^2, and the load N must not flicker from cell to cell.
    bool smooth_curvature = true;
    // Compute the coefficients tile by tile where they are first needed
    // (TerrainFields::ensure, terrain.hpp) rather than every cell at once: the same
    // values, and a small flow on a large DEM leaves the rest of the terrain untouched.
    bool on_demand = true;
};

// Terrain coefficients from a DEM on the grid, z in metres, solver orientation
// (index j * nx + i, j = 0 the southern row). Gradients are central differences
// (one-sided on the edges). The elevation is set at once; the other fields are made on
// demand unless options.on_demand is false.
TerrainFields dem_terrain(const Grid& grid, const std::vector<double>& z, double gravity,
                          const DemFrameOptions& options = {});

}  // namespace avalanche
