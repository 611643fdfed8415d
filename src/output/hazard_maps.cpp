#include "avalanche/output/hazard_maps.hpp"

#include <algorithm>
#include <cmath>

namespace avalanche {

HazardClass classify(double max_depth, double max_pressure_kpa, const OutputParams& p) {
    if (!(max_depth >= p.h_threshold)) return HazardClass::none;
    if (max_pressure_kpa >= p.pressure_high_kpa) return HazardClass::high;
    if (max_pressure_kpa >= p.pressure_low_kpa) return HazardClass::medium;
    return HazardClass::low;
}

double true_speed(const State& s, const TerrainFields& t, int i, int j) {
    const double h = s.h(i, j);
    if (h <= 0.0) return 0.0;
    const double u = s.hu(i, j) / h, v = s.hv(i, j) / h;
    double speed2 = u * u + v * v;
    if (t.has_metric) {
        const double w = t.sx(i, j) * u + t.sy(i, j) * v;  // vertical component on the bed
        speed2 += w * w;
    }
    return std::sqrt(speed2);
}

HazardMaps::HazardMaps(const Grid& grid, const OutputParams& params, double density)
    : grid_(grid),
      params_(params),
      density_(density),
      max_depth_(grid.cells()),
      max_speed_(grid.cells()),
      arrival_(grid.cells()),
      deposit_(grid.cells()) {}

// Outside reach_box_ the maps hold zeros: pressure_kpa(0) = +0, which the vector starts
// with.
std::vector<double> HazardMaps::max_pressure() const {
    std::vector<double> out(max_speed_.size());
    for_each_cell(reach_box_, grid_.nx, [&](int, int, std::size_t k) {
        out[k] = pressure_kpa(max_speed_[k]);
    });
    return out;
}

std::vector<double> HazardMaps::arrival_time() const {
    std::vector<double> out(arrival_.size(), kNotReached);
    for_each_cell(reach_box_, grid_.nx, [&](int, int, std::size_t k) { out[k] = arrival_time(k); });
    return out;
}

// A checkpoint holds the maps as they read (arrival -1 where not reached, docs/io.md).
void HazardMaps::save(CheckpointData& c) const {
    c.reals["hazard_maps/max_depth"].assign(max_depth_.begin(), max_depth_.end());
    c.reals["hazard_maps/max_speed"].assign(max_speed_.begin(), max_speed_.end());
    c.reals["hazard_maps/arrival_time"] = arrival_time();
}

void HazardMaps::restore(const CheckpointData& c) {
    const auto n = static_cast<long long>(grid_.cells());
    // Read all three before assigning any: a bad checkpoint leaves the maps untouched.
    const auto& depth = c.real("hazard_maps/max_depth", n);
    const auto& speed = c.real("hazard_maps/max_speed", n);
    const auto& arrival = c.real("hazard_maps/arrival_time", n);
    // Fresh maps written only where the flow was, as the run left them.
    CellVector<double> d(depth.size()), s(speed.size()), a(arrival.size());
    ActiveBox box;
    for (std::size_t k = 0; k < depth.size(); ++k) {
        if (depth[k] != 0.0) d[k] = depth[k];
        if (speed[k] != 0.0) s[k] = speed[k];
        if (depth[k] >= params_.h_threshold) a[k] = arrival[k];
        if (depth[k] != 0.0 || speed[k] != 0.0) {
            const int i = static_cast<int>(k % static_cast<std::size_t>(grid_.nx));
            const int j = static_cast<int>(k / static_cast<std::size_t>(grid_.nx));
            box = box.united({i, i + 1, j, j + 1});
        }
    }
    max_depth_ = std::move(d);
    max_speed_ = std::move(s);
    arrival_ = std::move(a);
    reach_box_ = box;
}

// Cells with enough of them share the work between threads: the maps are a pass
// over the cells of every step (a larger bound than the solver's passes, whose cells
// cost more).
constexpr std::size_t kMinCellsPerThreadedMapPass = 20000;

// The cells of `boxes` (rows of the box the view holds), row by row.
void HazardMaps::accumulate(const SimulationView& v, std::span<const ActiveBox> boxes) {
    reach_box_ = reach_box_.united(v.box);
    std::size_t cells = 0;
    rows_.clear();
    for (const ActiveBox& b : boxes) {
        if (b.empty()) continue;
        cells += b.cells();
        for (int j = b.j0; j < b.j1; ++j) rows_.push_back({j, b.i0, b.i1});
    }
    const int n = static_cast<int>(rows_.size());
#pragma omp parallel for schedule(static) if (cells >= kMinCellsPerThreadedMapPass)
    for (int q = 0; q < n; ++q) {
        const auto [j, i0, i1] = rows_[static_cast<std::size_t>(q)];
        accumulate_row(v, j, i0, i1);
    }
}

void HazardMaps::accumulate_row(const SimulationView& v, int j, int i0, int i1) {
    const double thr = params_.h_threshold;
    for (int i = i0; i < i1; ++i) {
        const double hn = v.state.h(i, j) * v.terrain.normal_thickness(i, j);
        if (hn <= 0.0) continue;
        const std::size_t k = static_cast<std::size_t>(j) * grid_.nx + i;
        // Speeds and pressures of the thin-layer film below h_thr are not hazard:
        // they are the numerical wet/dry layer, not flowing material.
        if (!is_flowing(hn, thr)) {
            max_depth_[k] = std::max(max_depth_[k], hn);
            continue;
        }
        if (!reached(k)) arrival_[k] = v.t;  // reached for the first time
        max_depth_[k] = std::max(max_depth_[k], hn);
        max_speed_[k] = std::max(max_speed_[k], true_speed(v.state, v.terrain, i, j));
    }
}

// The active box holds every wet cell (observer.hpp): outside it h = 0, nothing to
// accumulate, and the terrain there may not even be made (terrain.hpp) -- reading it
// would touch memory no run needs.
void HazardMaps::on_start(const SimulationView& v) { accumulate(v, {&v.box, 1}); }

// Only the cells the step may have changed (the view's changed boxes, else the whole
// box): every other cell of the box holds the state the maps took in at an earlier
// step, and maxima and first arrivals of the same state are what they were (on a valley
// of settled films a fourth of the box's cells).
void HazardMaps::on_step(const SimulationView& v) {
    accumulate(v, v.changed.empty() ? std::span<const ActiveBox>{&v.box, 1} : v.changed);
}

void HazardMaps::on_end(const SimulationView& v) {
    // deposit_ starts as zeros; only the active box can hold material (on_start).
    reach_box_ = reach_box_.united(v.box);
    for (int j = v.box.j0; j < v.box.j1; ++j)
        for (int i = v.box.i0; i < v.box.i1; ++i) {
            const double hn = v.state.h(i, j) * v.terrain.normal_thickness(i, j);
            // The deposit map shows material, not the thin-layer film.
            deposit_[static_cast<std::size_t>(j) * grid_.nx + i] = hn >= params_.h_threshold ? hn : 0.0;
        }
}

// Outside reach_box_ no cell is reached: HazardClass::none, the vector's zeros.
std::vector<std::uint8_t> HazardMaps::hazard_classes() const {
    std::vector<std::uint8_t> out(grid_.cells());
    for_each_cell(reach_box_, grid_.nx, [&](int, int, std::size_t k) {
        out[k] = static_cast<std::uint8_t>(classify(max_depth_[k], max_pressure(k), params_));
    });
    return out;
}

}  // namespace avalanche
