#pragma once
// DIR/results.h5: the snapshots of a run (docs/io.md has the layout). An observer of
// the time loop that appends h (bed-normal), u and v at every output time, so a long
// run never holds more than one snapshot in memory. Rows are flipped here to the
// GeoTIFF convention (row 0 at the top); this is the only place that flips.
// The file is written as results.h5.part and renamed by finish(), so a results.h5
// that exists is always complete.
#include <array>
#include <cstddef>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "avalanche/core/grid.hpp"
#include "avalanche/core/observer.hpp"
#include "avalanche/core/simulation.hpp"
#include "avalanche/physics/terrain.hpp"

namespace avalanche {

struct ResultsMetadata {
    std::array<double, 6> geotransform{};  // GDAL convention, row 0 at the top
    std::string crs_wkt;                   // empty in the chute frame
    Frame frame = Frame::chute;
    double gravity = 9.81;  // m/s^2
    double h_min = 0.0;     // effective thin-layer depth (m)
    nlohmann::json config;  // effective_config(scenario)
    std::string config_hash;
};

class ResultsWriter : public StepObserver {
  public:
    // Creates `final_path`.part and writes the root attributes.
    ResultsWriter(std::string final_path, const Grid& grid, const ResultsMetadata& meta);
    ~ResultsWriter() override;
    ResultsWriter(const ResultsWriter&) = delete;
    ResultsWriter& operator=(const ResultsWriter&) = delete;

    void on_output(const SimulationView& view) override;

    // Writes the end-of-run attributes, closes the file and renames it into place.
    void finish(const RunStatistics& stats);

    // Checkpoints: copies the snapshots written so far into the open HDF5 file `file`
    // (an hid_t) as /results/{time,h,u,v}; `file_path` names it in errors.
    void copy_snapshots_to(std::int64_t file, const std::string& file_path) const;
    // Resume: replaces the (empty) snapshots by those saved in `checkpoint_path`, so
    // the run continues appending after them; throws InputError if they are not there
    // or do not fit the grid.
    void resume_from(const std::string& checkpoint_path);

    [[nodiscard]] std::size_t snapshots() const;
    [[nodiscard]] const std::string& path() const { return final_path_; }

  private:
    struct Impl;  // HDF5 handles stay out of this header
    std::string final_path_;
    std::unique_ptr<Impl> impl_;
};

}  // namespace avalanche
