#include "avalanche/output/monitoring.hpp"

#include <cmath>

#include "avalanche/output/hazard_maps.hpp"

namespace avalanche {

MonitoringPoints::MonitoringPoints(std::vector<ProbeLocation> points, double interval, double density)
    : points_(std::move(points)), interval_(interval), density_(density), series_(points_.size()) {}

void MonitoringPoints::sample(const SimulationView& v) {
    for (std::size_t p = 0; p < points_.size(); ++p) {
        const int i = points_[p].i, j = points_[p].j;
        const double h = v.state.h(i, j);
        const double u = h > 0.0 ? v.state.hu(i, j) / h : 0.0;
        const double vv = h > 0.0 ? v.state.hv(i, j) / h : 0.0;
        const double speed = true_speed(v.state, v.terrain, i, j);
        series_[p].push_back(
            {v.t, h * v.terrain.normal_thickness(i, j), u, vv, speed, density_ * speed * speed / 1000.0});
    }
    next_ = (std::floor(v.t / interval_ + 1e-9) + 1.0) * interval_;
}

void MonitoringPoints::on_step(const SimulationView& v) {
    if (v.t >= next_ - 1e-12 * next_) sample(v);
}

void MonitoringPoints::on_end(const SimulationView& v) {
    if (series_.empty() || series_.front().empty() || series_.front().back().t < v.t) sample(v);
}

}  // namespace avalanche
