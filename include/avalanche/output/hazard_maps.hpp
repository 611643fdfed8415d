#pragma once
// Per-cell hazard maps accumulated over a run (MODEL.md section 5), as an observer
// of the time loop. Everything here is physics post-processing without I/O; the
// GIS layer writes the maps.
//
// Conventions: depths are BED-NORMAL thickness (state h x normal_thickness); the
// velocity is the TRUE along-surface speed (the DEM frame adds the vertical
// component of the projected velocity); impact pressure is rho |u|^2 in kPa.
// "Reached" means h >= h_threshold.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "avalanche/core/field_storage.hpp"
#include "avalanche/core/observer.hpp"
#include "avalanche/numerics/active_box.hpp"
#include "avalanche/output/output_params.hpp"

namespace avalanche {

// Hazard intensity classes, from the maximum impact pressure of a reached cell:
// 3 high (p >= pressure_high_kpa), 2 medium (p >= pressure_low_kpa), 1 low
// (reached, p below the low limit), 0 not reached.
enum class HazardClass : std::uint8_t { none = 0, low = 1, medium = 2, high = 3 };

HazardClass classify(double max_depth, double max_pressure_kpa, const OutputParams& p);

// Along-surface speed of a cell from the state (0 for a dry cell).
double true_speed(const State& s, const TerrainFields& t, int i, int j);

// Whether a layer of bed-normal thickness hn counts as flowing material, whose speed and
// pressure the maps (and the monitoring series) take in: at least h_threshold. A thinner
// layer is the numerical wet/dry layer a flow leaves; only its depth counts.
[[nodiscard]] inline bool is_flowing(double hn, double h_threshold) { return !(hn < h_threshold); }

// Storage: every map starts as untouched zeros (CellVector, core/field_storage.hpp), so
// on a large DEM only the pages of cells the flow reaches are ever made -- a small
// release on a 2000 x 2000 grid no longer writes 32 B/cell of maps it never fills. Hence
// two maps are not stored as they read: the arrival time is kept only for reached cells
// (a cell is reached exactly when its maximum depth is at least h_threshold, which is
// positive), and the maximum pressure is rho |u|^2 of the maximum speed -- x -> rho x x
// is monotonic in rounded arithmetic too, so it is to the bit the maximum over the
// steps of the pressure the step would have computed.
class HazardMaps : public StepObserver {
public:
    HazardMaps(const Grid& grid, const OutputParams& params, double density);

    void on_start(const SimulationView& v) override;
    void on_step(const SimulationView& v) override;
    void on_end(const SimulationView& v) override;

    // Dense nx*ny maps in solver orientation (index k = j * nx + i).
    [[nodiscard]] std::span<const double> max_depth() const { return max_depth_; }      // m
    [[nodiscard]] std::span<const double> max_speed() const { return max_speed_; }      // m/s
    [[nodiscard]] std::span<const double> deposit_depth() const { return deposit_; }    // m, at the end
    // Maximum impact pressure rho |u|^2 (kPa): of one cell, and the whole map.
    [[nodiscard]] double max_pressure(std::size_t k) const { return pressure_kpa(max_speed_[k]); }
    [[nodiscard]] std::vector<double> max_pressure() const;
    // First time the cell was reached (s); kNotReached where never: of one cell, and the
    // whole map.
    [[nodiscard]] double arrival_time(std::size_t k) const { return reached(k) ? arrival_[k] : kNotReached; }
    [[nodiscard]] std::vector<double> arrival_time() const;
    [[nodiscard]] std::vector<std::uint8_t> hazard_classes() const;
    [[nodiscard]] const Grid& grid() const { return grid_; }
    // A box that holds every cell where a map holds a value (the union of the active
    // boxes the maps were accumulated over; empty before any): outside it every map
    // reads zero, i.e. not reached. Readers of whole maps look only inside it -- on a
    // large DEM the rest of the maps' memory is never touched, and a first read of an
    // untouched page costs a page fault (docs/performance.md, "Maps read where the flow
    // went").
    [[nodiscard]] const ActiveBox& reach_box() const { return reach_box_; }

    static constexpr double kNotReached = -1.0;

    // Checkpoints: the maxima and arrival times so far ("hazard_maps/..."); the
    // deposit is taken from the state at the end, so it is not saved.
    void save(CheckpointData& c) const override;
    void restore(const CheckpointData& c) override;

private:
    void accumulate(const SimulationView& v, std::span<const ActiveBox> boxes);
    void accumulate_row(const SimulationView& v, int j, int i0, int i1);
    [[nodiscard]] bool reached(std::size_t k) const { return max_depth_[k] >= params_.h_threshold; }
    // The expression the step used when it kept a pressure map: (rho * s) * s.
    [[nodiscard]] double pressure_kpa(double speed) const { return density_ / 1000.0 * speed * speed; }

    Grid grid_;
    OutputParams params_;
    double density_;
    // arrival_ holds a time only where reached(k); elsewhere it stays 0.
    CellVector<double> max_depth_, max_speed_, arrival_, deposit_;
    ActiveBox reach_box_;
    std::vector<std::array<int, 3>> rows_;  // accumulate's rows: j, first and end column
};

}  // namespace avalanche
