#include "avalanche/output/monitoring.hpp"

#include <cmath>

#include "avalanche/core/error.hpp"
#include "avalanche/output/hazard_maps.hpp"

namespace avalanche {

MonitoringPoints::MonitoringPoints(std::vector<ProbeLocation> points, double interval,
                                   double density, double h_threshold)
    : points_(std::move(points)),
      interval_(interval),
      density_(density),
      h_threshold_(h_threshold),
      series_(points_.size()) {}

void MonitoringPoints::sample(const SimulationView& v) {
    for (std::size_t p = 0; p < points_.size(); ++p) {
        const int i = points_[p].i, j = points_[p].j;
        const double h = v.state.h(i, j);
        const double hn = h * v.terrain.normal_thickness(i, j);
        // The maps' rule (is_flowing): the layers a flow leaves thinner than h_thr slide on
        // at the speed of the track (about 20 m/s on the demo's): shown, they drew
        // 110-140 kPa at the demo's point for the last 16 s of its run, under a layer
        // thinning from 6 to 0.05 mm.
        const bool flowing = is_flowing(hn, h_threshold_);
        const double u = flowing ? v.state.hu(i, j) / h : 0.0;
        const double vv = flowing ? v.state.hv(i, j) / h : 0.0;
        const double speed = flowing ? true_speed(v.state, v.terrain, i, j) : 0.0;
        series_[p].push_back({v.t, hn, u, vv, speed, density_ * speed * speed / 1000.0});
    }
    next_ = (std::floor(v.t / interval_ + 1e-9) + 1.0) * interval_;
}

void MonitoringPoints::on_step(const SimulationView& v) {
    if (v.t >= next_ - 1e-12 * next_) sample(v);
}

void MonitoringPoints::on_end(const SimulationView& v) {
    if (series_.empty() || series_.front().empty() || series_.front().back().t < v.t) sample(v);
}

namespace {
constexpr std::size_t kSampleFields = 6;  // t, h, u, v, speed, pressure
}

void MonitoringPoints::save(CheckpointData& c) const {
    std::vector<std::int64_t> counts;
    std::vector<double> samples;
    for (const auto& series : series_) {
        counts.push_back(static_cast<std::int64_t>(series.size()));
        for (const ProbeSample& s : series) samples.insert(samples.end(), {s.t, s.h, s.u, s.v, s.speed, s.pressure});
    }
    c.integers["monitoring/sample_counts"] = counts;
    c.reals["monitoring/samples"] = samples;
    c.reals["monitoring/next_sample_time"] = {next_};
}

void MonitoringPoints::restore(const CheckpointData& c) {
    const auto& counts = c.integer("monitoring/sample_counts", static_cast<long long>(points_.size()));
    std::size_t total = 0;
    for (std::int64_t n : counts) {
        if (n < 0) throw InputError("checkpoint", "dataset monitoring/sample_counts holds a negative count");
        total += static_cast<std::size_t>(n);
    }
    const auto& samples = c.real("monitoring/samples", static_cast<long long>(total * kSampleFields));
    const double next = c.real("monitoring/next_sample_time", 1).front();
    std::vector<std::vector<ProbeSample>> series(points_.size());
    std::size_t k = 0;
    for (std::size_t p = 0; p < points_.size(); ++p)
        for (std::int64_t n = 0; n < counts[p]; ++n, k += kSampleFields)
            series[p].push_back({samples[k], samples[k + 1], samples[k + 2], samples[k + 3], samples[k + 4],
                                 samples[k + 5]});
    series_ = std::move(series);
    next_ = next;
}

}  // namespace avalanche
