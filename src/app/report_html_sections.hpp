#pragma once
// The sections of a run's report.html below the maps (report_html_sections.cpp).
#include <nlohmann/json.hpp>
#include <string>

#include "avalanche/app/products.hpp"

namespace avalanche::detail {

// Table of the points' arrival and maxima (from the summary) and plots of depth, speed and
// pressure against time (from the monitoring series). "" without monitoring points.
std::string monitoring_section(const ProductInputs& in, const nlohmann::json& summary);

// End reason, simulated time, mass balance and throughput.
std::string run_section(const nlohmann::json& summary);

// The effective configuration, one row per parameter.
std::string parameters_section(const nlohmann::json& summary);

// Input files with their SHA-256, the software version and the exact command line.
std::string provenance_section(const nlohmann::json& summary);

}  // namespace avalanche::detail
