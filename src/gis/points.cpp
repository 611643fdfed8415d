// Monitoring points from CSV (own parser, for line-numbered errors) or OGR layers.
#include "avalanche/gis/points.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "crs_support.hpp"
#include "gdal_support.hpp"

namespace avalanche::gis {

namespace {

struct RawPoint {
    std::string name;
    double x, y;
    std::string where;  // "line 4" or "layer 'p' feature 2", for messages
};

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t\r");
    std::string t = s.substr(b, e - b + 1);
    if (t.size() >= 2 && t.front() == '"' && t.back() == '"') t = t.substr(1, t.size() - 2);
    return t;
}

std::vector<std::string> split_csv(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(trim(cell));
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    return cells;
}

bool parse_number(const std::string& text, double& value) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end && !text.empty() && std::isfinite(value);
}

std::vector<RawPoint> read_csv(std::istream& in, const std::string& path) {
    std::string line;
    int number = 0;
    int col_name = -1, col_x = -1, col_y = -1;
    std::size_t columns = 0;
    std::vector<RawPoint> points;
    while (std::getline(in, line)) {
        ++number;
        // The byte-order mark spreadsheets put before "CSV UTF-8" text: invisible in a
        // message, it would make the header's first column unknown.
        if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
        const std::string t = trim(line);
        if (t.empty() || t.front() == '#') continue;
        const auto cells = split_csv(line);
        if (col_name < 0) {  // header
            for (std::size_t k = 0; k < cells.size(); ++k) {
                const std::string h = detail::lower(cells[k]);
                if (h == "name") col_name = static_cast<int>(k);
                if (h == "x") col_x = static_cast<int>(k);
                if (h == "y") col_y = static_cast<int>(k);
            }
            if (col_name < 0 || col_x < 0 || col_y < 0)
                throw InputError(path, "line " + std::to_string(number) +
                                           ": expected a header with columns name,x,y, got '" + t +
                                           "'");
            columns = cells.size();
            continue;
        }
        const std::string where = "line " + std::to_string(number);
        if (cells.size() != columns)
            throw InputError(path, where + ": " + std::to_string(cells.size()) +
                                       " columns where the header has " + std::to_string(columns) +
                                       " ('" + t + "')");
        RawPoint p{cells[col_name], 0.0, 0.0, where};
        if (p.name.empty()) throw InputError(path, where + ": empty point name");
        if (!parse_number(cells[col_x], p.x) || !parse_number(cells[col_y], p.y))
            throw InputError(path, where + ": x and y must be numbers, got '" + cells[col_x] +
                                       "' and '" + cells[col_y] + "'");
        points.push_back(p);
    }
    if (col_name < 0) throw InputError(path, "empty file; expected a header name,x,y");
    return points;
}

std::vector<RawPoint> read_csv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw InputError(path, "cannot open the file");
    return read_csv(in, path);
}

std::string name_of(OGRFeature& f) {
    for (const char* field : {"name", "NAME", "Name", "id", "ID", "Id"}) {
        const int k = f.GetFieldIndex(field);
        if (k >= 0 && f.IsFieldSetAndNotNull(k)) {
            const std::string s = trim(f.GetFieldAsString(k));
            if (!s.empty()) return s;
        }
    }
    return "point_" + std::to_string(f.GetFID());
}

// OGR points, already transformed into the grid CRS.
std::vector<RawPoint> read_ogr(const std::string& path, const OGRSpatialReference& grid_srs,
                               const detail::GdalErrorScope& errors) {
    detail::DatasetPtr ds = detail::open_vector(path, errors);
    std::vector<RawPoint> points;
    for (OGRLayer* layer : detail::geometry_layers(*ds)) {
        const OGRSpatialReference* srs = layer->GetSpatialRef();
        detail::TransformPtr ct;
        if (srs != nullptr && !srs->IsEmpty() && !grid_srs.IsEmpty() && !srs->IsSame(&grid_srs))
            ct = detail::make_transform(*srs, grid_srs, path);
        for (auto& f : *layer) {
            const std::string where = "layer '" + std::string(layer->GetName()) + "' feature " +
                                      std::to_string(f->GetFID());
            const OGRGeometry* g = f->GetGeometryRef();
            if (g == nullptr || wkbFlatten(g->getGeometryType()) != wkbPoint || g->IsEmpty())
                throw InputError(path, where + ": expected a point geometry");
            double x = g->toPoint()->getX(), y = g->toPoint()->getY();
            if (ct && !ct->Transform(1, &x, &y))
                throw InputError(path, where + ": cannot reproject to the grid CRS");
            points.push_back({name_of(*f), x, y, where});
        }
    }
    return points;
}

}  // namespace

std::vector<CsvPoint> parse_points_csv(const std::string& text, const std::string& label) {
    std::istringstream in(text);
    std::vector<CsvPoint> out;
    for (const RawPoint& p : read_csv(in, label)) out.push_back({p.name, p.x, p.y, p.where});
    return out;
}

std::vector<MonitoringPoint> read_points(const std::string& path, const std::string& csv_crs,
                                         const GeoGrid& geo) {
    detail::GdalErrorScope errors;
    const OGRSpatialReference grid_srs = detail::srs_from_text(geo.crs_wkt, "crs");
    const std::string ext = detail::lower(std::filesystem::path(path).extension().string());
    std::vector<RawPoint> raw;
    if (ext == ".csv" || ext == ".txt") {
        std::error_code ec;
        if (!std::filesystem::exists(path, ec)) throw InputError(path, "file not found");
        raw = read_csv(path);
        const OGRSpatialReference from = detail::srs_from_text(csv_crs, "points_crs");
        if (!from.IsEmpty() && !grid_srs.IsEmpty() && !from.IsSame(&grid_srs)) {
            detail::TransformPtr ct = detail::make_transform(from, grid_srs, path);
            for (auto& p : raw)
                if (!ct->Transform(1, &p.x, &p.y))
                    throw InputError(path, p.where + ": cannot reproject to the grid CRS");
        }
    } else {
        raw = read_ogr(path, grid_srs, errors);
    }
    if (raw.empty()) throw InputError(path, "contains no point");

    const Grid& g = geo.grid;
    std::set<std::string> names;
    std::vector<MonitoringPoint> points;
    for (const auto& p : raw) {
        if (!names.insert(p.name).second)
            throw InputError(path, p.where + ": duplicate point name '" + p.name + "'");
        // The name becomes the point's group in monitoring.h5, where '/' separates groups
        // and "." is the file's root group: refused now rather than when that file is
        // written, after the whole simulation.
        if (p.name == "." || p.name.find('/') != std::string::npos)
            throw InputError(path, p.where + ": point name '" + p.name +
                                       "' cannot name a group of monitoring.h5; expected a "
                                       "name without '/' and other than '.'");
        if (!(p.x >= g.x0 && p.x < g.x_max() && p.y >= g.y0 && p.y < g.y_max())) {
            std::ostringstream msg;
            msg.precision(10);
            msg << p.where << ": point '" << p.name << "' at x=" << p.x << ", y=" << p.y
                << " lies outside the grid (x " << g.x0 << ".." << g.x_max() << ", y " << g.y0
                << ".." << g.y_max() << ")";
            throw InputError(path, msg.str());
        }
        const int i = std::min(g.nx - 1, static_cast<int>(std::floor((p.x - g.x0) / g.dx)));
        const int j = std::min(g.ny - 1, static_cast<int>(std::floor((p.y - g.y0) / g.dy)));
        points.push_back({p.name, p.x, p.y, i, j});
    }
    return points;
}

}  // namespace avalanche::gis
