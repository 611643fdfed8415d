#pragma once
// report.html: the planner's report of a run and of a batch (docs/products.md, "Planner's
// report"). One self-contained file each: images as data: URIs, plots and overlays as
// inline SVG, CSS inline, no script and no external URL, so it opens offline and prints.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "avalanche/app/products.hpp"

namespace avalanche {

// DIR/report.html of a run. Every number of the run comes from `summary` (the object that
// becomes summary.json) and carries its key, e.g. <td data-key="runout.runout_length_m">;
// the maps embed DIR/<map>.png, so write_products must have run. Returns "report.html".
std::string write_report_html(const std::string& dir, const ProductInputs& in,
                              const nlohmann::json& summary);

// DIR/report.html of a batch, from the files the batch wrote into DIR: comparison.csv,
// and of `batch_files` (the names this batch wrote, e.g. "runout_vs_delta_deg.svg") the
// *_vs_*.svg plots, impact_frequency.tif (drawn into impact_frequency.png over the
// hillshade of the first scenario's dem.tif) and calibration.json. Files of an earlier
// batch in DIR that are not listed are not shown. Returns the file names written.
std::vector<std::string> write_batch_report_html(const std::string& dir,
                                                 const std::string& base_scenario,
                                                 const std::vector<std::string>& batch_files);

}  // namespace avalanche
