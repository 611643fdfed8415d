#pragma once
// Time series of h, u, v, speed and impact pressure at named monitoring points,
// sampled at every step that crosses a multiple of the sampling interval (and at
// the start and end), from the cell that contains the point. As in the hazard maps,
// velocities, speeds and pressures are those of flowing material: zero while the
// bed-normal thickness is below h_threshold (the thickness itself is always given).
#include <string>
#include <vector>

#include "avalanche/core/observer.hpp"

namespace avalanche {

struct ProbeLocation {
    std::string name;
    double x = 0.0, y = 0.0;  // grid coordinates (m)
    int i = 0, j = 0;         // cell
};

struct ProbeSample {
    double t;        // s
    double h;        // bed-normal thickness (m)
    double u, v;     // grid-direction velocity components (m/s)
    double speed;    // along-surface speed (m/s)
    double pressure; // kPa
};

class MonitoringPoints : public StepObserver {
public:
    // density (kg/m^3) for the impact pressure; h_threshold (m, bed-normal), the maps'
    // OutputParams::h_threshold.
    MonitoringPoints(std::vector<ProbeLocation> points, double interval, double density,
                     double h_threshold);

    void on_start(const SimulationView& v) override { sample(v); }
    void on_step(const SimulationView& v) override;
    void on_end(const SimulationView& v) override;

    [[nodiscard]] const std::vector<ProbeLocation>& points() const { return points_; }
    // series()[p] is the time series of point p.
    [[nodiscard]] const std::vector<std::vector<ProbeSample>>& series() const { return series_; }

    // Checkpoints: the series so far and the next sampling time ("monitoring/...").
    void save(CheckpointData& c) const override;
    void restore(const CheckpointData& c) override;

private:
    void sample(const SimulationView& v);

    std::vector<ProbeLocation> points_;
    double interval_, density_, h_threshold_;
    double next_ = 0.0;
    std::vector<std::vector<ProbeSample>> series_;
};

}  // namespace avalanche
