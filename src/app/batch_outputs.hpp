#pragma once
// The across-scenario outputs of a batch (docs/batch.md), all built from what each
// scenario wrote into DIR/<id>/ (summary.json and the GeoTIFF maps), so that scenarios
// skipped on resume and scenarios computed now are treated alike.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "avalanche/app/batch_plan.hpp"

namespace avalanche::detail {

struct BatchResult {
    const BatchCase* batch_case = nullptr;
    std::string dir;                        // DIR/<id>
    std::optional<nlohmann::json> summary;  // its summary.json; empty if it failed
    std::string failure;                    // the error, if it failed
};

// The swept parameters, in the order of the first case's values.
std::vector<const SweepParameter*> swept_parameters(const std::vector<BatchResult>& rows);

// DIR/comparison.csv (one row per scenario, sorted by id) and DIR/comparison.md; plots
// DIR/<metric>_vs_<parameter>.svg for each numeric swept parameter. Returns file names.
std::vector<std::string> write_comparison(const std::string& dir,
                                          const std::vector<BatchResult>& rows,
                                          const std::string& base_scenario);

// DIR/impact_frequency.tif and DIR/envelope_*.tif from the complete scenarios' maps.
// Returns the file names written (none without a complete scenario).
std::vector<std::string> write_envelopes(const std::string& dir,
                                         const std::vector<BatchResult>& rows);

}  // namespace avalanche::detail
