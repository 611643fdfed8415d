#pragma once
// Building blocks shared by the run and batch reports (report_html*.cpp).
#include <nlohmann/json.hpp>
#include <string>

namespace avalanche::detail {

// The value at a dotted key ("runout.runout_length_m", "monitoring_points.0.name"; array
// indices as numbers); null when absent.
const nlohmann::json* json_at(const nlohmann::json& root, const std::string& dotted_key);

// A JSON value for a reader: numbers by format_number (integers exactly), strings as they
// are, null as `null_text`, arrays comma-separated.
std::string json_text(const nlohmann::json& value, const std::string& null_text = "none");

// <tag class="v" data-key="key">value</tag>: a number of the summary, marked so that tests
// and scripts can find it. A missing key gives "n/a" without data-key.
std::string keyed(const nlohmann::json& root, const std::string& key, const char* tag = "span",
                  const std::string& null_text = "none");

// A complete HTML page with the report's stylesheet inline.
std::string html_document(const std::string& title, const std::string& body);

// The whole file as bytes; "" when it cannot be read.
std::string read_file_bytes(const std::string& path);

}  // namespace avalanche::detail
