// Observed deposit polygons (any OGR source and CRS) -> cell mask on the solver grid.
// The reading rules follow release_polygons.cpp (same cell-centre rule, same CRS
// handling) so an outline drawn like a release area lands on the same cells.
#include <gdal_alg.h>

#include <memory>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/observed.hpp"
#include "crs_support.hpp"
#include "orientation.hpp"

namespace avalanche::gis {

namespace {

bool is_polygonal(const OGRGeometry& g) {
    const auto type = wkbFlatten(g.getGeometryType());
    return type == wkbPolygon || type == wkbMultiPolygon || type == wkbCurvePolygon ||
           type == wkbMultiSurface;
}

std::string label_of(OGRLayer& layer, OGRFeature& f) {
    return "layer '" + std::string(layer.GetName()) + "' feature " + std::to_string(f.GetFID());
}

std::string extent_text(const OGREnvelope& e, const Grid& g) {
    std::ostringstream msg;
    msg.precision(10);
    msg << "polygon x " << e.MinX << ".." << e.MaxX << ", y " << e.MinY << ".." << e.MaxY
        << "; grid x " << g.x0 << ".." << g.x_max() << ", y " << g.y0 << ".." << g.y_max();
    return msg.str();
}

}  // namespace

ObservedFootprint rasterize_observed_polygons(const std::string& path, const GeoGrid& geo) {
    detail::GdalErrorScope errors;
    detail::DatasetPtr ds = detail::open_vector(path, errors);
    const OGRSpatialReference grid_srs = detail::srs_from_text(geo.crs_wkt, "crs");
    const Grid& g = geo.grid;

    std::vector<std::unique_ptr<OGRGeometry>> polygons;  // in the grid CRS
    bool reprojected = false, assumed_crs = false;
    for (OGRLayer* layer : detail::geometry_layers(*ds)) {
        const OGRSpatialReference* layer_srs = layer->GetSpatialRef();
        detail::TransformPtr to_grid;
        if (layer_srs == nullptr || layer_srs->IsEmpty()) {
            assumed_crs = true;
        } else if (!grid_srs.IsEmpty() && !layer_srs->IsSame(&grid_srs)) {
            to_grid = detail::make_transform(*layer_srs, grid_srs, path);
            reprojected = true;
        }
        layer->ResetReading();
        for (auto& feature : *layer) {
            const std::string label = label_of(*layer, *feature);
            const OGRGeometry* geometry = feature->GetGeometryRef();
            if (geometry == nullptr || geometry->IsEmpty())
                throw InputError(path, label + " has no geometry");
            if (!is_polygonal(*geometry))
                throw InputError(path, label + " is a " + geometry->getGeometryName() +
                                           "; the observed deposit must be polygons");
            if (!geometry->IsValid())
                throw InputError(path, label +
                                           " has an invalid geometry (self-intersecting or "
                                           "badly formed rings); repair it, e.g. with QGIS "
                                           "'Fix geometries'");
            std::unique_ptr<OGRGeometry> p = detail::linear_copy(*geometry);
            if (to_grid && p->transform(to_grid.get()) != OGRERR_NONE)
                throw InputError(path, label + " cannot be reprojected to " + geo.crs_label());
            OGREnvelope e;
            p->getEnvelope(&e);
            if (e.MaxX <= g.x0 || e.MinX >= g.x_max() || e.MaxY <= g.y0 || e.MinY >= g.y_max())
                throw InputError(
                    path, label + " lies entirely outside the DEM: " + extent_text(e, g) + " in " +
                              (geo.crs_wkt.empty() ? std::string("grid coordinates (no CRS)")
                                                   : geo.crs_label()) +
                              (to_grid ? " (after reprojection)" : ""));
            polygons.push_back(std::move(p));
        }
    }
    if (polygons.empty())
        throw InputError(path, "contains no polygon; expected the observed deposit as polygons");

    // All polygons burnt at once on the whole grid (GDAL's default cell-centre rule).
    detail::DatasetPtr mem = detail::mem_for_grid(geo, 1, GDT_Byte);
    std::vector<OGRGeometryH> handles;
    for (const auto& p : polygons) handles.push_back(OGRGeometry::ToHandle(p.get()));
    int band = 1;
    const std::vector<double> burn(handles.size(), 1.0);
    if (GDALRasterizeGeometries(GDALDataset::ToHandle(mem.get()), 1, &band,
                                static_cast<int>(handles.size()), handles.data(), nullptr, nullptr,
                                burn.data(), nullptr, nullptr, nullptr) != CE_None)
        throw Error(ExitCode::internal, "GDALRasterizeGeometries failed for " + path);
    const std::vector<double> burnt = detail::read_solver_rows(*mem, 1, g, path);

    ObservedFootprint out;
    out.inside.assign(burnt.size(), 0);
    for (std::size_t k = 0; k < burnt.size(); ++k)
        if (burnt[k] > 0.5) {
            out.inside[k] = 1;
            ++out.cells;
        }
    out.polygons = static_cast<int>(polygons.size());
    if (out.cells == 0)
        throw InputError(
            path, "its polygons cover no cell centre of the " + std::to_string(g.dx) + " m grid");
    std::ostringstream s;
    s << "observed deposit " << path << ": " << out.polygons << " polygon(s) on " << out.cells
      << " cells (cell-centre rule)";
    if (reprojected) s << ", reprojected to " << geo.crs_label();
    if (assumed_crs && !geo.crs_wkt.empty())
        s << "; a layer without CRS was taken to be in " << geo.crs_label();
    out.description = s.str();
    return out;
}

}  // namespace avalanche::gis
