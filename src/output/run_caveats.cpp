#include "avalanche/output/run_caveats.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace avalanche {

EdgeContact edge_contact(const Grid& grid, std::span<const double> max_depth, double h_threshold,
                         std::span<const std::uint8_t> sinks) {
    return edge_contact(grid, max_depth, h_threshold, sinks, ActiveBox{0, grid.nx, 0, grid.ny});
}

EdgeContact edge_contact(const Grid& grid, std::span<const double> max_depth, double h_threshold,
                         std::span<const std::uint8_t> sinks, const ActiveBox& reach) {
    EdgeContact c;
    const int nx = grid.nx, ny = grid.ny;
    if (nx <= 0 || ny <= 0) return c;
    const ActiveBox b = reach.clipped(nx, ny);
    if (b.empty()) return c;
    auto k = [nx](int i, int j) { return static_cast<std::size_t>(j) * nx + i; };
    auto reached = [&](int i, int j) { return max_depth[k(i, j)] >= h_threshold; };
    for (int j = b.j0; j < b.j1; ++j) {
        if (b.i0 == 0) c.low_i += reached(0, j);
        if (b.i1 == nx) c.high_i += reached(nx - 1, j);
    }
    for (int i = b.i0; i < b.i1; ++i) {
        if (b.j0 == 0) c.low_j += reached(i, 0);
        if (b.j1 == ny) c.high_j += reached(i, ny - 1);
    }
    if (sinks.empty()) return c;
    auto sink = [&](int i, int j) {
        return i >= 0 && i < nx && j >= 0 && j < ny && sinks[k(i, j)] != 0;
    };
    for (int j = b.j0; j < b.j1; ++j)
        for (int i = b.i0; i < b.i1; ++i)
            if (reached(i, j) &&
                (sink(i, j) || sink(i - 1, j) || sink(i + 1, j) || sink(i, j - 1) || sink(i, j + 1)))
                ++c.beside_no_data;
    return c;
}

namespace {

std::string printed(const char* format, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
}

// Whole cubic metres from 100 m3 on (the report's style), three digits below.
std::string volume_text(double v) { return printed(v >= 100.0 ? "%.0f" : "%.3g", v); }

std::string percent_text(double fraction) {
    return printed(fraction >= 0.001 ? "%.1f" : "%.2g", 100.0 * fraction);
}

std::string cells_text(int n) { return std::to_string(n) + (n == 1 ? " cell" : " cells"); }

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& items) {
    std::string s;
    for (std::size_t n = 0; n < items.size(); ++n) {
        if (n > 0) s += n + 1 == items.size() ? " and " : ", ";
        s += items[n];
    }
    return s;
}

RunCaveat reached_edge(const CaveatInputs& in) {
    const EdgeContact& e = in.edges;
    const bool dem = in.frame == Frame::dem;
    // Solver orientation (core/grid.hpp): i grows to the east, or down the chute; j
    // grows to the north, or across the chute.
    const struct {
        int cells;
        const char* dem_side;
        const char* chute_side;
    } sides[] = {{e.low_i, "the west side", "the upper end"},
                 {e.high_i, "the east side", "the lower end"},
                 {e.low_j, "the south side", "the side y = 0"},
                 {e.high_j, "the north side", "the side y = width"}};
    std::vector<std::string> where;
    for (const auto& s : sides)
        if (s.cells > 0) where.push_back(std::string(dem ? s.dem_side : s.chute_side) + " (" + cells_text(s.cells) + ")");
    if (e.beside_no_data > 0) where.push_back("the DEM's no-data area (" + cells_text(e.beside_no_data) + ")");

    const RunStatistics& st = in.stats;
    std::string m = where.empty() ? "Layers of the flow thinner than h_threshold (" + printed("%g", in.h_threshold) +
                                        " m) reached the end of the terrain"
                                  : "The flow reached the end of the terrain: " + listed(where);
    if (st.outflow_volume > 0.0) {
        const double fraction = st.released_volume > 0.0 ? st.outflow_volume / st.released_volume : 0.0;
        m += "; " + volume_text(st.outflow_volume) + " m3 (" + percent_text(fraction) +
             " % of the release) left the grid there";
    } else if (in.numerics.boundary == Boundary::wall) {
        m += "; the grid's edges are walls (numerics.boundary = \"wall\") and held it there";
    }
    m += where.empty() ? ". That material is missing from the deposit, and on a larger terrain the flow "
                         "might have gone farther: "
                       : ". The runout, the affected area and the deposit end at the edge of the grid, so the "
                         "maps understate the hazard beyond it: ";
    m += dem ? "extend the DEM beyond the edges it reached." : "lengthen or widen the chute.";
    return {"reached_edge", m};
}

RunCaveat not_stopped(const CaveatInputs& in) {
    const double fraction = in.stats.final_kinetic_energy_fraction();
    const NumericsParams& n = in.numerics;
    std::string m = "The flow had not stopped at t_end = " + printed("%.6g", in.stats.simulated_time) +
                    " s: its kinetic energy was " + printed("%.2g", fraction) + " of its maximum";
    const std::string rule = "the stop rule needs below " + printed("%.2g", n.stop_ke_fraction) + " for " +
                             printed("%.3g", n.stop_duration) + " s";
    // Below a hundredth the main flow is over (docs/numerics.md, "End of a run": thin
    // layers sliding on slopes steeper than delta hold the energy up, and near the
    // threshold it crosses it back and forth); above it the flow is in full motion and
    // the maps are a snapshot of it.
    if (fraction < 0.01)
        m += ", the main flow over, but " + rule +
             "; thin layers sliding on slopes steeper than delta can keep a run from stopping. "
             "Check with a longer run (--t-end, numerics.t_end) that the runout and the deposit "
             "no longer change.";
    else
        m += " (" + rule +
             "). deposit_thickness.tif holds material that was still moving, and the runout and "
             "the affected area may still grow: run longer (--t-end, numerics.t_end).";
    return {"not_stopped", m};
}

}  // namespace

std::vector<RunCaveat> run_caveats(const CaveatInputs& in) {
    std::vector<RunCaveat> caveats;
    if (in.stats.end_reason == EndReason::interrupted) return caveats;
    // Films thinner than h_threshold leave without any edge cell counting as reached
    // (avaKot on 20 m cells: 0.1 % of the release into the no-data area, the affected
    // area well inside): a caveat only once a hundredth of the release is missing.
    const bool left = in.stats.released_volume > 0.0 &&
                      in.stats.outflow_volume >= 0.01 * in.stats.released_volume;
    if (in.edges.any() || left) caveats.push_back(reached_edge(in));
    if (in.stats.end_reason == EndReason::end_time) caveats.push_back(not_stopped(in));
    return caveats;
}

}  // namespace avalanche
