#include "paper_chute.hpp"

#include <algorithm>
#include <cmath>

#include "avalanche/core/observer.hpp"
#include "avalanche/output/hazard_maps.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche::validation {

namespace {

// Bed-normal depth on the centre line y = width/2: the middle row for odd ny, the mean
// of the two middle rows for even ny (the centre line is then their common edge).
std::vector<double> centre_line(const Grid& g, const TerrainFields& t, const State& s) {
    std::vector<double> h(g.nx);
    const int j1 = g.ny / 2, j0 = g.ny % 2 == 1 ? j1 : j1 - 1;
    for (int i = 0; i < g.nx; ++i)
        h[i] = 0.5 * (s.h(i, j0) * t.normal_thickness(i, j0) + s.h(i, j1) * t.normal_thickness(i, j1));
    return h;
}

// Records the centre-line front and tail at the snapshots nearest the probe times.
class ProbeObserver : public StepObserver {
public:
    ProbeObserver(const ChuteCase& c, std::vector<double> x) : case_(c), x_(std::move(x)) {
        probes_.resize(c.probe_times.size());
        for (std::size_t k = 0; k < probes_.size(); ++k) probes_[k].t = c.probe_times[k];
    }
    void on_output(const SimulationView& v) override {
        // Snapshots are hit exactly at multiples of output_interval; a probe time is
        // taken at the snapshot within half an interval of it.
        const double half = 0.5 * case_.numerics.output_interval;
        for (std::size_t k = 0; k < probes_.size(); ++k) {
            if (std::abs(v.t - case_.probe_times[k]) > half || done_[k]) continue;
            FrontTail f = front_tail(x_, centre_line(v.grid, v.terrain, v.state), case_.front_threshold);
            f.t = v.t;
            probes_[k] = f;
            done_[k] = true;
        }
    }
    void on_start(const SimulationView&) override { done_.assign(probes_.size(), false); }
    [[nodiscard]] const std::vector<FrontTail>& probes() const { return probes_; }

private:
    const ChuteCase& case_;
    std::vector<double> x_;
    std::vector<FrontTail> probes_;
    std::vector<bool> done_;
};

// Position where h crosses `thr` between cell centres a (below) and b (at or above).
double crossing(double xa, double ha, double xb, double hb, double thr) {
    if (hb == ha) return xb;
    return xa + (thr - ha) / (hb - ha) * (xb - xa);
}

}  // namespace

FrontTail front_tail(const std::vector<double>& x, const std::vector<double>& h, double threshold) {
    FrontTail f;
    int first = -1, last = -1;
    for (int i = 0; i < static_cast<int>(h.size()); ++i) {
        f.max_depth = std::max(f.max_depth, h[i]);
        if (h[i] < threshold) continue;
        if (first < 0) first = i;
        last = i;
    }
    if (first < 0) return f;
    f.found = true;
    const int n = static_cast<int>(h.size());
    f.tail = first > 0 ? crossing(x[first - 1], h[first - 1], x[first], h[first], threshold) : x[first];
    f.front = last + 1 < n ? crossing(x[last + 1], h[last + 1], x[last], h[last], threshold) : x[last];
    return f;
}

ChuteOutcome run_chute_case(const ChuteCase& c) {
    ChuteOutcome out;
    const Grid grid = chute_grid(c.geometry, c.cell_size);
    const TerrainFields terrain = chute_terrain(c.geometry, grid, c.numerics.gravity);
    const State initial =
        state_at_rest(grid, rasterize_release(ReleaseShape{c.cap}, grid), terrain);
    out.x.resize(grid.nx);
    for (int i = 0; i < grid.nx; ++i) out.x[i] = grid.x_center(i);
    out.toe_x = c.geometry.transition_end.value_or(0.0);

    Simulation sim(grid, terrain, c.material, c.numerics, initial,
                   effective_h_min(c.numerics, initial, terrain));
    OutputParams params;
    params.h_threshold = c.front_threshold;
    HazardMaps maps(grid, params, c.material.density);
    ProbeObserver probes(c, out.x);
    sim.add_observer(&maps);
    sim.add_observer(&probes);
    out.stats = sim.run();
    out.probes = probes.probes();

    const ChuteGeometry geometry = c.geometry;
    out.runout = compute_runout(
        grid, terrain, initial, maps, params,
        [geometry, grid](int i, int j) {
            return std::array<double, 2>{geometry.horizontal_distance(grid.x_center(i)),
                                         grid.y_center(j)};
        },
        grid.cell_area());

    out.deposit = centre_line(grid, terrain, sim.state());
    out.deposit_extent = front_tail(out.x, out.deposit, c.front_threshold);
    double y_lo = 1e300, y_hi = -1e300;
    for (int j = 0; j < grid.ny; ++j)
        for (int i = 0; i < grid.nx; ++i) {
            const double d = maps.deposit_depth()[static_cast<std::size_t>(j) * grid.nx + i];
            out.deposit_max_depth = std::max(out.deposit_max_depth, d);
            if (d < c.front_threshold) continue;
            y_lo = std::min(y_lo, grid.y_center(j) - 0.5 * grid.dy);
            y_hi = std::max(y_hi, grid.y_center(j) + 0.5 * grid.dy);
        }
    out.deposit_width = y_hi > y_lo ? y_hi - y_lo : 0.0;
    return out;
}

ChuteCase paper_chute(double slope_deg, double delta_deg, double phi_deg, double cell_size) {
    ChuteCase c;
    c.geometry.slope_deg = slope_deg;
    c.geometry.length = 150.0;
    c.geometry.width = 60.0;
    c.geometry.transition_start = 25.0;
    c.geometry.transition_end = 30.0;
    c.geometry.runout_slope_deg = 0.0;
    c.cap.center = {7.5, 30.0};
    c.cap.radius = 2.5;
    c.material.phi_deg = phi_deg;
    c.material.delta_deg = delta_deg;
    c.material.earth_pressure = EarthPressureModel::savage_hutter;
    c.material.density = 2000.0;
    c.numerics.scheme = Scheme::waf;
    c.numerics.cfl = 0.2;
    c.numerics.t_end = 120.0;
    c.numerics.output_interval = 1.0;
    c.cell_size = cell_size;
    return c;
}

}  // namespace avalanche::validation
