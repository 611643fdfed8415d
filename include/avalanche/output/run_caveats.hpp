#pragma once
// What a run's maps do not say by themselves: the reasons they may understate the hazard.
// Two are detected after every run:
//   reached_edge  the flow reached the end of the terrain (a side of the grid, or the
//                 DEM's no-data area, whose cells are sinks): the runout, the affected
//                 area and the deposit stop there, and what left is not on any map (also
//                 when only layers below h_threshold got there but a hundredth of the
//                 release left with them);
//   not_stopped   the run ended at t_end with the flow still moving: the deposit holds
//                 moving material and the runout may still grow.
// The log (as warnings), summary.json ("caveats"), report.md, report.html and a batch's
// comparison.csv all print this one list. Post-processing without I/O.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/numerics/parameters.hpp"
#include "avalanche/output/output_params.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

// Reached cells (maximum depth at least h_threshold) where the terrain ends, in solver
// orientation: on the i = 0, i = nx - 1, j = 0 and j = ny - 1 edges (a corner counts on
// both of its sides), and inside the grid beside (4-neighbour) or on a sink cell.
struct EdgeContact {
    int low_i = 0, high_i = 0, low_j = 0, high_j = 0;
    int beside_no_data = 0;
    [[nodiscard]] bool any() const { return low_i + high_i + low_j + high_j + beside_no_data > 0; }
};

// max_depth: nx * ny, index j * nx + i; sinks: the same size, or empty for none.
EdgeContact edge_contact(const Grid& grid, std::span<const double> max_depth, double h_threshold,
                         std::span<const std::uint8_t> sinks);
// The same where no cell outside `reach` is reached (the maps' HazardMaps::reach_box),
// read only inside it: on a tile of 13 M cells the whole grid took 0.13 s a run.
EdgeContact edge_contact(const Grid& grid, std::span<const double> max_depth, double h_threshold,
                         std::span<const std::uint8_t> sinks, const ActiveBox& reach);

struct RunCaveat {
    std::string code;     // "reached_edge" or "not_stopped"
    std::string message;  // one sentence with the numbers and what to do
};

struct CaveatInputs {
    const RunStatistics& stats;
    EdgeContact edges;
    Frame frame = Frame::dem;  // names the sides: west/east/south/north, or the chute's ends
    const NumericsParams& numerics;
    double h_threshold = OutputParams{}.h_threshold;  // m: what counts as reached
};

// The caveats of a finished run, reached_edge first. An interrupted run has none here:
// its products are marked incomplete instead.
std::vector<RunCaveat> run_caveats(const CaveatInputs& in);

}  // namespace avalanche
