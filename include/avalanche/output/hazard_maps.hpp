#pragma once
// Per-cell hazard maps accumulated over a run (MODEL.md section 5), as an observer
// of the time loop. Everything here is physics post-processing without I/O; the
// GIS layer writes the maps.
//
// Conventions: depths are BED-NORMAL thickness (state h x normal_thickness); the
// velocity is the TRUE along-surface speed (the DEM frame adds the vertical
// component of the projected velocity); impact pressure is rho |u|^2 in kPa.
// "Reached" means h >= h_threshold.
#include <cstdint>
#include <vector>

#include "avalanche/core/observer.hpp"
#include "avalanche/output/output_params.hpp"

namespace avalanche {

// Hazard intensity classes, from the maximum impact pressure of a reached cell:
// 3 high (p >= pressure_high_kpa), 2 medium (p >= pressure_low_kpa), 1 low
// (reached, p below the low limit), 0 not reached.
enum class HazardClass : std::uint8_t { none = 0, low = 1, medium = 2, high = 3 };

HazardClass classify(double max_depth, double max_pressure_kpa, const OutputParams& p);

// Along-surface speed of a cell from the state (0 for a dry cell).
double true_speed(const State& s, const TerrainFields& t, int i, int j);

class HazardMaps : public StepObserver {
public:
    HazardMaps(const Grid& grid, const OutputParams& params, double density);

    void on_start(const SimulationView& v) override;
    void on_step(const SimulationView& v) override;
    void on_end(const SimulationView& v) override;

    // Dense nx*ny maps in solver orientation (index j * nx + i).
    [[nodiscard]] const std::vector<double>& max_depth() const { return max_depth_; }        // m
    [[nodiscard]] const std::vector<double>& max_speed() const { return max_speed_; }        // m/s
    [[nodiscard]] const std::vector<double>& max_pressure() const { return max_pressure_; }  // kPa
    // First time the cell was reached (s); kNotReached where never.
    [[nodiscard]] const std::vector<double>& arrival_time() const { return arrival_; }
    [[nodiscard]] const std::vector<double>& deposit_depth() const { return deposit_; }      // m, at the end
    [[nodiscard]] std::vector<std::uint8_t> hazard_classes() const;
    [[nodiscard]] const Grid& grid() const { return grid_; }

    static constexpr double kNotReached = -1.0;

    // Checkpoints: the maxima and arrival times so far ("hazard_maps/..."); the
    // deposit is taken from the state at the end, so it is not saved.
    void save(CheckpointData& c) const override;
    void restore(const CheckpointData& c) override;

private:
    void accumulate(const SimulationView& v, int i0, int i1, int j0, int j1);

    Grid grid_;
    OutputParams params_;
    double density_;
    std::vector<double> max_depth_, max_speed_, max_pressure_, arrival_, deposit_;
};

}  // namespace avalanche
