#pragma once
// Monitoring points: named locations where the solver records time series.
#include <string>
#include <vector>

#include "avalanche/gis/geo_grid.hpp"

namespace avalanche::gis {

struct MonitoringPoint {
    std::string name;
    double x = 0.0, y = 0.0;  // grid CRS (m)
    int i = 0, j = 0;         // cell holding the point, solver orientation (j = 0 south)
};

// Reads points from
//  - a CSV file (.csv / .txt): a header with columns name, x, y (any order, other
//    columns ignored; '#' lines and blank lines skipped), coordinates in `csv_crs`
//    ("" = the grid CRS);
//  - any OGR point layer (GeoPackage, GeoJSON, Shapefile...), in its own CRS; the
//    name comes from a `name` / `NAME` / `id` field, else "point_<FID>".
// Throws InputError naming the file and the line / feature for malformed rows, points
// outside the grid and duplicate names; ConfigError("points_crs") for a bad csv_crs.
std::vector<MonitoringPoint> read_points(const std::string& path, const std::string& csv_crs,
                                         const GeoGrid& geo);

// A point as written in a CSV file, before any reprojection or grid check.
struct CsvPoint {
    std::string name;
    double x = 0.0, y = 0.0;
    std::string where;  // "line 4", for messages
};

// The CSV parser of read_points, from text (fuzzing, tests); `label` names the source in
// errors. Throws InputError(label, "line N: ...") for a missing header column, a row
// with the wrong number of cells, an empty name or a coordinate that is not a finite
// number, and for text without a header.
std::vector<CsvPoint> parse_points_csv(const std::string& text, const std::string& label);

}  // namespace avalanche::gis
