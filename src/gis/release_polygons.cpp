// Release polygons (any OGR source) -> bed-normal thickness per cell, cell-centre rule.
#include <gdal_alg.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/release.hpp"
#include "crs_support.hpp"
#include "orientation.hpp"

namespace avalanche::gis {

namespace {

constexpr const char* kDefaultThicknessField = "thickness";  // AvaFrame's attribute

struct Polygon {
    std::unique_ptr<OGRGeometry> geometry;  // in the grid CRS
    double thickness = 0.0;                 // bed-normal (m)
    std::string label;
};

std::string fields_of(OGRFeatureDefn* defn) {
    std::string out;
    for (int k = 0; k < defn->GetFieldCount(); ++k)
        out += (k ? ", " : "") + std::string(defn->GetFieldDefn(k)->GetNameRef());
    return out.empty() ? "none" : out;
}

int find_field(OGRFeatureDefn* defn, const std::string& name) {
    for (int k = 0; k < defn->GetFieldCount(); ++k)
        if (detail::lower(defn->GetFieldDefn(k)->GetNameRef()) == detail::lower(name)) return k;
    return -1;
}

std::string label_of(OGRLayer& layer, OGRFeature& f) {
    std::string label =
        "layer '" + std::string(layer.GetName()) + "' feature " + std::to_string(f.GetFID());
    const int name = find_field(f.GetDefnRef(), "name");
    if (name >= 0 && f.IsFieldSetAndNotNull(name))
        label += " (" + std::string(f.GetFieldAsString(name)) + ")";
    return label;
}

// A Shapefile is several files; GDAL's own message about a missing .shx is obscure.
void check_shapefile_sidecars(const std::string& path) {
    const std::filesystem::path p(path);
    if (detail::lower(p.extension().string()) != ".shp") return;
    for (const char* ext : {".shx", ".dbf"}) {
        std::filesystem::path lower_case = p, upper_case = p;
        lower_case.replace_extension(ext);
        upper_case.replace_extension(std::string(ext) == ".shx" ? ".SHX" : ".DBF");
        std::error_code ec;
        if (!std::filesystem::exists(lower_case, ec) && !std::filesystem::exists(upper_case, ec))
            throw InputError(path, "the Shapefile's " + std::string(ext) + " file (" +
                                       lower_case.filename().string() +
                                       ") is missing: copy all of its files (.shp, .shx, "
                                       ".dbf, .prj) together, or use a GeoPackage");
    }
}

double thickness_of(OGRFeature& f, int field, const std::string& field_name,
                    const std::string& label, const std::string& path) {
    const std::string where = label + ", field '" + field_name + "'";
    if (!f.IsFieldSetAndNotNull(field))
        throw InputError(path, where + ": empty; expected a bed-normal thickness in m");
    double value = 0.0;
    const OGRFieldType type = f.GetFieldDefnRef(field)->GetType();
    if (type == OFTReal || type == OFTInteger || type == OFTInteger64) {
        value = f.GetFieldAsDouble(field);
    } else if (type == OFTString) {
        const std::string text = f.GetFieldAsString(field);
        const auto first = text.find_first_not_of(" \t");
        const auto last = text.find_last_not_of(" \t");
        const char* begin = text.data() + (first == std::string::npos ? text.size() : first);
        const char* end = text.data() + (last == std::string::npos ? 0 : last + 1);
        const auto [ptr, ec] = std::from_chars(begin, end, value);
        if (ec != std::errc() || ptr != end || begin >= end)
            throw InputError(path, where + ": '" + text + "' is not a number (thickness in m)");
    } else {
        throw InputError(path, where + ": not a numeric field");
    }
    if (!std::isfinite(value) || value <= 0.0)
        throw InputError(path, where + ": " + std::to_string(value) +
                                   "; expected a positive bed-normal thickness in m");
    return value;
}

bool is_polygonal(const OGRGeometry& g) {
    const auto type = wkbFlatten(g.getGeometryType());
    return type == wkbPolygon || type == wkbMultiPolygon || type == wkbCurvePolygon ||
           type == wkbMultiSurface;
}

std::vector<Polygon> read_polygons(const std::string& path, const GeoGrid& geo,
                                   const ReleaseOptions& opts, detail::GdalErrorScope& errors,
                                   bool& any_layer_without_crs) {
    detail::DatasetPtr ds = detail::open_vector(path, errors);
    const OGRSpatialReference grid_srs = detail::srs_from_text(geo.crs_wkt, "crs");
    const Grid& g = geo.grid;
    std::vector<Polygon> polygons;
    std::string empty_layers;
    for (OGRLayer* layer : detail::geometry_layers(*ds)) {
        OGRFeatureDefn* defn = layer->GetLayerDefn();
        if (layer->GetFeatureCount(TRUE) == 0) {
            empty_layers +=
                (empty_layers.empty() ? "'" : ", '") + std::string(layer->GetName()) + "'";
            continue;
        }
        int field = -1;
        std::string field_name = opts.thickness_field;
        if (!opts.thickness) {
            if (field_name.empty()) field_name = kDefaultThicknessField;
            field = find_field(defn, field_name);
            if (field < 0 && opts.thickness_field.empty())
                throw ConfigError("thickness",
                                  "no release thickness given, and layer '" +
                                      std::string(layer->GetName()) + "' of " + path +
                                      " has no 'thickness' field (fields: " + fields_of(defn) +
                                      "); give a thickness or a thickness field");
            if (field < 0)
                throw InputError(path, "layer '" + std::string(layer->GetName()) +
                                           "' has no field '" + field_name +
                                           "' (fields: " + fields_of(defn) + ")");
        }
        const OGRSpatialReference* layer_srs = layer->GetSpatialRef();
        detail::TransformPtr to_grid;
        if (layer_srs == nullptr || layer_srs->IsEmpty())
            any_layer_without_crs = true;
        else if (!grid_srs.IsEmpty() && !layer_srs->IsSame(&grid_srs))
            to_grid = detail::make_transform(*layer_srs, grid_srs, path);

        layer->ResetReading();
        for (auto& feature : *layer) {
            Polygon p;
            p.label = label_of(*layer, *feature);
            const OGRGeometry* geometry = feature->GetGeometryRef();
            if (geometry == nullptr || geometry->IsEmpty())
                throw InputError(path, p.label + " has no geometry");
            if (!is_polygonal(*geometry))
                throw InputError(path, p.label + " is a " + geometry->getGeometryName() +
                                           "; release areas must be polygons");
            errors.clear();
            if (!geometry->IsValid()) {
                const std::string why =
                    errors.warnings().empty() ? "" : ": " + errors.warnings().back();
                throw InputError(path, p.label +
                                           " has an invalid geometry (self-intersecting "
                                           "or badly formed rings" +
                                           why + "); repair it, e.g. with QGIS 'Fix geometries'");
            }
            p.thickness = opts.thickness ? *opts.thickness
                                         : thickness_of(*feature, field, field_name, p.label, path);
            p.geometry = detail::linear_copy(*geometry);
            if (to_grid && p.geometry->transform(to_grid.get()) != OGRERR_NONE)
                throw InputError(path, p.label + " cannot be reprojected to " + geo.crs_label());
            OGREnvelope e;
            p.geometry->getEnvelope(&e);
            if (e.MaxX <= g.x0 || e.MinX >= g.x_max() || e.MaxY <= g.y0 || e.MinY >= g.y_max()) {
                std::ostringstream msg;
                msg.precision(10);
                msg << p.label << " lies entirely outside the DEM: polygon x " << e.MinX << ".."
                    << e.MaxX << ", y " << e.MinY << ".." << e.MaxY << "; grid x " << g.x0 << ".."
                    << g.x_max() << ", y " << g.y0 << ".." << g.y_max() << " in " << geo.crs_label()
                    << (layer_srs == nullptr ? " (the layer has no CRS: assumed to be the grid's)"
                                             : "");
                throw InputError(path, msg.str());
            }
            polygons.push_back(std::move(p));
        }
    }
    if (polygons.empty())
        throw InputError(path, "contains no release polygon (empty layer" +
                                   (empty_layers.empty() ? std::string("s") : " " + empty_layers) +
                                   ")");
    return polygons;
}

// Burns one polygon on the sub-grid of cells under its envelope (cell-centre rule) and
// returns the covered cells as solver indices of the full grid.
std::vector<std::size_t> cells_under(const Polygon& p, const GeoGrid& geo) {
    const Grid& g = geo.grid;
    OGREnvelope e;
    p.geometry->getEnvelope(&e);
    const int i0 = std::max(0, static_cast<int>(std::floor((e.MinX - g.x0) / g.dx)));
    const int i1 = std::min(g.nx, static_cast<int>(std::ceil((e.MaxX - g.x0) / g.dx)));
    const int j0 = std::max(0, static_cast<int>(std::floor((e.MinY - g.y0) / g.dy)));
    const int j1 = std::min(g.ny, static_cast<int>(std::ceil((e.MaxY - g.y0) / g.dy)));
    if (i1 <= i0 || j1 <= j0) return {};
    GeoGrid window{Grid{i1 - i0, j1 - j0, g.dx, g.dy, g.x0 + i0 * g.dx, g.y0 + j0 * g.dy}, ""};
    detail::DatasetPtr mem = detail::mem_for_grid(window, 1, GDT_Byte);
    int band = 1;
    double burn = 1.0;
    OGRGeometryH handle = OGRGeometry::ToHandle(p.geometry.get());
    if (GDALRasterizeGeometries(GDALDataset::ToHandle(mem.get()), 1, &band, 1, &handle, nullptr,
                                nullptr, &burn, nullptr, nullptr, nullptr) != CE_None)
        throw Error(ExitCode::internal, "GDALRasterizeGeometries failed for " + p.label);
    const std::vector<double> burnt = detail::read_solver_rows(*mem, 1, window.grid, p.label);
    std::vector<std::size_t> cells;
    for (int b = 0; b < window.grid.ny; ++b)
        for (int a = 0; a < window.grid.nx; ++a)
            if (burnt[static_cast<std::size_t>(b) * window.grid.nx + a] > 0.5)
                cells.push_back(static_cast<std::size_t>(j0 + b) * g.nx + (i0 + a));
    return cells;
}

}  // namespace

Release rasterize_release_polygons(const std::string& path, const GeoGrid& geo,
                                   const ReleaseOptions& opts) {
    detail::GdalErrorScope errors;
    if (opts.thickness && !opts.thickness_field.empty())
        throw ConfigError("thickness", "give either a thickness or a thickness field, not both");
    if (opts.thickness && (!std::isfinite(*opts.thickness) || *opts.thickness <= 0.0))
        throw ConfigError("thickness", "expected a positive bed-normal thickness in m");
    check_shapefile_sidecars(path);
    bool assumed_crs = false;
    const std::vector<Polygon> polygons = read_polygons(path, geo, opts, errors, assumed_crs);

    Release r;
    r.thickness.assign(geo.grid.cells(), 0.0);
    r.feature_id.assign(geo.grid.cells(), 0);
    r.features = static_cast<int>(polygons.size());
    r.feature_cells.assign(polygons.size(), 0);
    for (std::size_t k = 0; k < polygons.size(); ++k) {
        const Polygon& p = polygons[k];
        const std::vector<std::size_t> cells = cells_under(p, geo);
        if (cells.empty())
            throw InputError(path, p.label + " covers no cell centre of the " +
                                       std::to_string(geo.grid.dx) +
                                       " m grid; enlarge it or use a finer grid");
        for (std::size_t c : cells) {
            if (p.thickness <= r.thickness[c]) continue;  // the thicker polygon owns a cell
            if (r.feature_id[c] > 0) --r.feature_cells[r.feature_id[c] - 1];
            r.thickness[c] = p.thickness;
            r.feature_id[c] = static_cast<int>(k) + 1;
            ++r.feature_cells[k];
        }
        r.feature_labels.push_back(p.label);
    }
    std::ostringstream s;
    s << "Rasterized " << r.features << " release polygon(s) from " << path
      << " onto the grid (cell-centre rule";
    if (assumed_crs) s << "; a layer without CRS was taken to be in " << geo.crs_label();
    s << "):";
    for (std::size_t k = 0; k < polygons.size(); ++k)
        s << " " << r.feature_labels[k] << " " << polygons[k].thickness << " m on "
          << r.feature_cells[k] << " cells;";
    r.description_of_steps = s.str();
    return r;
}

}  // namespace avalanche::gis
