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

// How well a scenario matches an observed deposit (--observed; batch_calibration.cpp,
// formulas in docs/batch.md).
struct ScenarioFit {
    double jaccard = 0.0;  // |observed AND simulated| / |observed OR simulated| (cells)
    std::size_t intersection_cells = 0, union_cells = 0;
    double simulated_runout_m = 0.0;  // summary.json runout.runout_length_m
    double observed_runout_m = 0.0;   // farthest observed cell from the same release top
    double runout_error_m = 0.0;      // simulated - observed
    double score = 0.0;               // (1 - jaccard) + |runout error| / max(observed, dx)
    int rank = 0;                     // 1 = best fit among the complete scenarios
};

// What became of a scenario in this batch (from the manifest).
enum class ScenarioOutcome {
    complete,     // now or in an earlier batch (skipped on resume)
    failed,       // an error stopped it: BatchResult::failure
    interrupted,  // Ctrl-C or SIGTERM stopped it; its folder holds its partial products
    not_run,      // the batch was stopped before it started
};

// comparison.csv's end_reason for a scenario without a summary: "failed", "interrupted",
// "not run".
const char* outcome_label(ScenarioOutcome outcome);

struct BatchResult {
    const BatchCase* batch_case = nullptr;
    std::string dir;                        // DIR/<id>
    std::optional<nlohmann::json> summary;  // its summary.json; only when complete
    std::string failure;                    // the error, if it failed
    std::optional<ScenarioFit> fit;         // with --observed, for complete scenarios
    ScenarioOutcome outcome = ScenarioOutcome::complete;
};

// The swept parameters, in the order of the first case's values.
std::vector<const SweepParameter*> swept_parameters(const std::vector<BatchResult>& rows);

// DIR/comparison.csv (one row per scenario, sorted by id) and DIR/comparison.md; plots
// DIR/<metric>_vs_<parameter>.svg for each numeric swept parameter. Returns file names.
// With `observed` (the --observed file), the fit columns and the ranking section are
// added from each row's `fit`.
std::vector<std::string> write_comparison(const std::string& dir,
                                          const std::vector<BatchResult>& rows,
                                          const std::string& base_scenario,
                                          const std::string& observed = "");

// DIR/impact_frequency.tif and DIR/envelope_*.tif from the complete scenarios' maps.
// Returns the file names written (none without a complete scenario).
std::vector<std::string> write_envelopes(const std::string& dir,
                                         const std::vector<BatchResult>& rows);

}  // namespace avalanche::detail
