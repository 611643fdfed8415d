// GeoTIFF (any GDAL raster) -> solver Grid + values; rows flipped by read_solver_rows,
// the one place that knows the orientation (STYLE.md 10).
#include <array>
#include <cmath>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/raster_reader.hpp"
#include "orientation.hpp"

namespace avalanche::gis {

RasterData read_geotiff(const std::string& path) {
    detail::GdalErrorScope errors;
    detail::DatasetPtr ds = detail::open_raster(path, errors);
    std::array<double, 6> gt{};
    if (ds->GetGeoTransform(gt.data()) != CE_None)
        throw InputError(path, "has no georeferencing (no geotransform)");
    if (gt[2] != 0.0 || gt[4] != 0.0 || !(gt[1] > 0.0) || !(gt[5] < 0.0))
        throw InputError(path, "is rotated or not north-up; expected a north-up raster");
    if (ds->GetRasterCount() < 1) throw InputError(path, "has no raster band");

    RasterData r;
    Grid& g = r.geo.grid;
    g.nx = ds->GetRasterXSize();
    g.ny = ds->GetRasterYSize();
    g.dx = gt[1];
    g.dy = -gt[5];
    g.x0 = gt[0];
    g.y0 = gt[3] - g.ny * g.dy;  // gt[3] is the north edge; the solver counts from the south
    if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
        char* wkt = nullptr;
        const char* options[] = {"FORMAT=WKT2", nullptr};
        if (srs->exportToWkt(&wkt, options) == OGRERR_NONE && wkt) r.geo.crs_wkt = wkt;
        CPLFree(wkt);
    }
    GDALRasterBand* band = ds->GetRasterBand(1);
    int has_nodata = 0;
    const double nodata = band->GetNoDataValue(&has_nodata);
    if (has_nodata) r.nodata = nodata;
    r.description = band->GetDescription();
    r.units = band->GetUnitType();
    r.values = detail::read_solver_rows(*ds, 1, g, path);
    if (errors.failed()) throw InputError(path, "cannot read the raster" + errors.reason());
    return r;
}

}  // namespace avalanche::gis
