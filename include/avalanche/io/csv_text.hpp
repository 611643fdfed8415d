#pragma once
// Text helper of the CSV files the program writes (monitoring.csv, comparison.csv).
#include <string>
#include <string_view>

namespace avalanche {

// One CSV field per RFC 4180: quoted, inner quotes doubled, when it holds ',', '"', CR or
// LF (names from GeoJSON or GeoPackage attributes may); unchanged otherwise, so ordinary
// names and numbers read as before.
std::string csv_field(std::string_view text);

}  // namespace avalanche
