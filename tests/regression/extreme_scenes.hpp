#pragma once
// Scenes of the extreme-case matrix (test_extremes.cpp): planes from 0 to 80 deg in
// both frames, DEM cliffs of 100 m between neighbouring cells, flows leaving through
// open edges, head-on collisions, grids down to 3 x 3. Each scene carries what the
// speed bound needs: the initial speed, the drop available and the release thickness.
#include <string>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/physics/material.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche::extremes {

enum class Kind {
    plane_dem,         // tilted-plane DEM falling along +x, paraboloid release upslope
    plane_chute,       // the same plane in the bed-fitted chute frame
    cliff_staircase,   // DEM steps of 100 m every 3 cells (flat treads), release on the top tread
    cliff_up,          // flat floor running into a 100 m wall, release moving at u0 toward it
    outflow,           // 40 deg plane, release next to the lower open edge: most of it leaves
    collision_flat,    // two boxes on a flat bed moving head on at +-u0
    collision_valley,  // V-shaped valley, one release on each flank, meeting on the thalweg
    single_cell,       // one wet cell in the middle of a tiny plane (3 x 3 and up)
};

struct Case {
    std::string name;
    Kind kind = Kind::plane_dem;
    double slope_deg = 30.0;  // plane, outflow and valley flank inclination
    double delta_deg = 20.0;
    double phi_deg = 35.0;
    double h0 = 1.0;     // release thickness, bed-normal (m)
    double h_min = 0.0;  // numerics.h_min (0: automatic, 1e-5 x h0)
    double cfl = 0.2;
    Splitting splitting = Splitting::lsl;
    bool rest_faces = false;  // numerics.rest_faces
    int n = 24;       // cells along x (y: kind-dependent)
    double u0 = 0.0;  // initial speed of moving releases (m/s)
    Scheme scheme = Scheme::waf;
    EarthPressureModel earth_pressure = EarthPressureModel::savage_hutter;
};

struct Scene {
    Grid grid;
    TerrainFields terrain;
    State initial;
    MaterialParams material;
    NumericsParams numerics;
    double drop = 0.0;  // highest release surface minus lowest bed (m)
    double u0 = 0.0;    // largest initial speed (m/s)
    double h0 = 0.0;    // largest bed-normal release thickness (m)
};

Scene make_scene(const Case& c);

// Sets the scene's drop, u0 and h0 from its terrain and initial state (make_scene
// calls it; scenes built elsewhere call it once their initial state is set).
void measure_release(Scene& s);

// Free-fall bound on any speed in the scene (m/s):
//   sqrt(u0^2 + 2 g drop) + 2 sqrt(k_max g h0).
// The first term is a point mass falling the whole drop without friction. The
// second is the release's own pressure potential: at a free front the pressure
// hands energy from the bulk to the front, which on a flat bed moves at 2 a0 =
// 2 sqrt(k g h0) (Ritter's dam break; on an incline x_front = 2 a0 t + g sin t^2 / 2,
// Mangeney et al. 2000, whose speed is sqrt(2 g drop + 4 a0^2) <= the sum). k_max is
// the largest earth-pressure coefficient of the material, so the bound holds in
// either regime. Friction only lowers speeds.
double speed_bound(const Scene& s);

// True (along-surface) speed of cell (i, j); 0 for an empty cell.
double true_speed(const Scene& s, const State& state, int i, int j);

}  // namespace avalanche::extremes
