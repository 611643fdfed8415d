#pragma once
// Calibration of a batch against an observed deposit (`batch --observed FILE`): each
// complete scenario's footprint is compared with the observed polygons on the
// computational grid, and the scenarios are ranked by fit (docs/batch.md).
#include <array>
#include <string>
#include <vector>

#include "avalanche/app/prepared_scene.hpp"
#include "avalanche/gis/observed.hpp"
#include "batch_outputs.hpp"

namespace avalanche::detail {

struct Observation {
    std::string path;
    gis::ObservedFootprint footprint;
    Grid grid;
    // Horizontal position of each observed cell, as compute_runout measures the
    // simulated tip (map coordinates in the DEM frame, along-slope distance in the chute).
    std::vector<std::array<double, 2>> positions;
    double cell_area_m2 = 0.0;
    double h_threshold = 0.0;  // output.h_threshold: the simulated footprint's depth
};

// Rasterises FILE on the grid of `scene` (InputError naming the file when unreadable,
// without polygons, or outside the DEM). Every scenario of a batch has this grid
// (cell_size cannot be swept), so one rasterisation serves them all.
Observation load_observation(const std::string& path, const PreparedScene& scene,
                             double h_threshold);

// Sets `fit` of every complete row from DIR/<id>/max_depth.tif and summary.json, then
// ranks them by score (ties by id).
void fit_to_observation(const Observation& observed, std::vector<BatchResult>& rows);

// DIR/calibration.json: the observation, the formulas' inputs and every scenario's fit,
// best first. Returns the file name.
std::string write_calibration(const std::string& dir, const Observation& observed,
                              const std::vector<BatchResult>& rows);

}  // namespace avalanche::detail
