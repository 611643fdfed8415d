#pragma once
// The parametric chute of the conservation and symmetry tests (MODEL.md section 4):
// a 45 deg plane, circular transition 25-30 m, horizontal runout, hemispherical
// cap of radius 2.5 m at (7.5, 20) on a 40 m wide chute. Optionally rough: a bed
// relief z_b = A cos(2 pi x / l) cos(2 pi (y - 20) / l) enters the chute frame only
// through the source a = -g cos(zeta) grad z_b (terrain.hpp), built mirror-exact
// about y = 20 so that the symmetry test stays bitwise.
#include <cstdint>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/physics/chute.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche::analytic {

struct ChuteScene {
    ChuteGeometry geometry;
    Grid grid;
    TerrainFields terrain;
    State initial;
};

// length: 60 m keeps the mass inside for ~10 s; a shorter chute (e.g. 30 m, no
// runout) lets it leave through the open lower edge. relief: amplitude A (m), 0 = smooth.
ChuteScene make_chute_scene(double cell_size, double length, double relief, double gravity = 9.81);

// A Simulation::run of the scene (Savage-Hutter, phi 35, delta 20 deg) on one thread
// to t_end with an observer that records, after every step, the smallest depth and the
// largest mirror asymmetry max |h(i, j) - h(i, ny-1-j)|; the state the run ends with.
struct ChuteOutcome {
    RunStatistics stats;
    double min_h = 0.0;
    double asymmetry = 0.0;
    std::uint64_t steps = 0;
    Grid grid;
    State final_state;
};
// n: the numerics (scheme, boundary, splitting, Courant number, t_end); the output
// interval is set to n.t_end.
ChuteOutcome run_chute(NumericsParams n, double cell_size, double length, double relief);
ChuteOutcome run_chute(Scheme scheme, Boundary boundary, double cell_size, double length,
                       double relief, double t_end);

}  // namespace avalanche::analytic
