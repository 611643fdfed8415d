#pragma once
// Shared machinery of the verification tests and the report tool: grids and
// plane terrains, a driver that advances a Stepper to an exact time, and the
// norms (L1 against exact cell averages, moments, threshold fronts, orders).
#include <functional>
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/state.hpp"
#include "avalanche/numerics/stepper.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche::analytic {

// [x_lo, x_hi] x [y_lo, y_hi] with square cells of size dx (must divide both).
Grid box_grid(double x_lo, double x_hi, double y_lo, double y_hi, double dx);
// A 1D problem: ny = 1 row of width dx over [x_lo, x_hi].
Grid line_grid(double x_lo, double x_hi, double dx);

// Bed-fitted plane of inclination slope_deg (chute frame, no curvature):
// a_x = g sin, p = g_n = g cos, a_y = 0.
TerrainFields plane_terrain(const Grid& g, double slope_deg, double gravity);

// Cell-averaged initial state from a depth function h(xa, xb, ya, yb) (cell
// average) and a velocity function (u, v) at the cell centre.
using CellAverage = std::function<double(double xa, double xb, double ya, double yb)>;
using PointVelocity = std::function<std::pair<double, double>(double x, double y)>;
State make_state(const Grid& g, const CellAverage& h, const PointVelocity& uv = {});

// Advances s from t to t_end with the stable dt (the last step shortened to land
// on t_end exactly). Returns the number of steps.
long advance_to(Stepper& stepper, State& s, double t, double t_end);

// Sum of |h - exact cell average| times the cell area over the interior (m^3, or m^2 in 1D
// per unit width).
double l1_depth_error(const State& s, const Grid& g, const CellAverage& exact);

// Moments of the depth: volume, centroid, and variance along x and y.
struct Moments {
    double volume = 0.0;
    double x_c = 0.0, y_c = 0.0;
    double var_x = 0.0, var_y = 0.0;
};
Moments depth_moments(const State& s, const Grid& g);

// Centre x of the last (downslope-most) / first cell of row j with h > level; NaN if none.
double last_x_above(const State& s, const Grid& g, int j, double level);
double first_x_below(const State& s, const Grid& g, int j, double level);

// Largest |h(i, j) - h(i, ny-1-j)| over the grid: zero for a mirror-symmetric state.
double mirror_asymmetry(const State& s, const Grid& g);
// Smallest h over the interior.
double min_depth(const State& s, const Grid& g);

// Runs the enclosed code on n OpenMP threads and restores the previous count. The
// solver parallelises over grid rows: a 1D problem has one row, so extra threads
// only add barriers; and on the shared 2-core CI machine (ctest -j2, other builds)
// spinning OpenMP barriers made a 2 s 2D run take 20-100 s. The verification
// studies are small, so they all run on one thread; results do not depend on it
// (every cell update is thread-independent, the volume sums are serial).
class ScopedThreads {
  public:
    static constexpr int kKeep = 0;  // leave the thread count as it is
    explicit ScopedThreads(int n);
    ~ScopedThreads();
    ScopedThreads(const ScopedThreads&) = delete;
    ScopedThreads& operator=(const ScopedThreads&) = delete;

  private:
    int saved_ = 1;
};

// Observed order of accuracy from errors on grids refined by `ratio`.
double observed_order(double e_coarse, double e_fine, double ratio = 2.0);

// Average of a fine 1D row onto a grid coarser by an integer factor.
std::vector<double> restrict_row(const std::vector<double>& fine, int factor);

// Default numerics with the given scheme (the studies vary only the scheme).
inline NumericsParams with_scheme(Scheme s) {
    NumericsParams n;
    n.scheme = s;
    return n;
}

}  // namespace avalanche::analytic
