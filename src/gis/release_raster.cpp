// Release thickness rasters, and the check that a release does not sit on filled voids.
#include <cmath>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/release.hpp"
#include "crs_support.hpp"
#include "orientation.hpp"
#include "warp.hpp"

namespace avalanche::gis {

std::vector<double> read_release_raster(const std::string& path, const GeoGrid& geo) {
    detail::GdalErrorScope errors;
    detail::DatasetPtr ds = detail::open_raster(path, errors);
    std::array<double, 6> gt{};
    if (ds->GetGeoTransform(gt.data()) != CE_None)
        throw InputError(path, "has no georeferencing (no geotransform)");

    // Negative thickness is an input error, not something to clip silently.
    GDALRasterBand* band = ds->GetRasterBand(1);
    double min_max[2] = {0.0, 0.0};
    errors.clear();
    if (band->ComputeRasterMinMax(FALSE, min_max) != CE_None) {
        if (errors.failed() && errors.reason().find("no valid pixels") == std::string::npos)
            throw InputError(path, "cannot read the raster values" + errors.reason());
        throw InputError(path, "holds no release thickness (every cell is nodata)");
    }
    if (min_max[0] < 0.0)
        throw InputError(path, "has negative release thickness (" + std::to_string(min_max[0]) +
                                   " m); expected bed-normal thickness >= 0 m");
    errors.clear();

    // Without a CRS the raster is taken to be in the grid's CRS (e.g. written by us).
    detail::DatasetPtr view;
    GDALDataset* source = ds.get();
    const OGRSpatialReference* srs = ds->GetSpatialRef();
    if ((srs == nullptr || srs->IsEmpty()) && !geo.crs_wkt.empty()) {
        GDALDriver* vrt = GetGDALDriverManager()->GetDriverByName("VRT");
        view.reset(vrt->CreateCopy("", ds.get(), FALSE, nullptr, nullptr, nullptr));
        if (!view) throw InputError(path, "cannot attach the grid CRS" + errors.reason());
        const OGRSpatialReference grid_srs = detail::srs_from_text(geo.crs_wkt, "crs");
        view->SetSpatialRef(&grid_srs);
        source = view.get();
    }
    // Averaging when coarsening keeps the released volume; bilinear otherwise. The source
    // spacing is compared in its own units only when they are the grid's (metres).
    const bool metric = srs == nullptr || srs->IsEmpty() || srs->IsProjected();
    const bool finer = metric && std::abs(gt[1]) < 0.75 * geo.grid.dx;
    detail::DatasetPtr warped =
        detail::warp_onto_grid({source}, geo, finer ? "average" : "bilinear", path, errors);
    std::vector<double> h = detail::read_solver_rows(*warped, 1, geo.grid, path);
    bool any = false;
    for (double& v : h) {
        if (!std::isfinite(v)) v = 0.0;  // nodata or outside the raster
        any = any || v > 0.0;
    }
    if (!any) throw InputError(path, "gives no release thickness on the grid (outside the DEM?)");
    return h;
}

void check_release_on_valid_dem(const std::vector<double>& thickness, const Dem& dem,
                                const std::string& release_path) {
    if (thickness.size() != dem.filled_mask.size())
        throw Error(ExitCode::internal, "release and DEM grids differ in size");
    int on_voids = 0;
    for (std::size_t k = 0; k < thickness.size(); ++k)
        if (thickness[k] > 0.0 && dem.filled_mask[k] != 0) ++on_voids;
    if (on_voids > 0)
        throw InputError(release_path,
                         std::to_string(on_voids) +
                             " release cells lie on DEM voids that were filled by "
                             "interpolation (no measured elevation); move the release "
                             "or use a DEM without voids there");
}

void check_release_on_valid_dem(const Release& release, const Dem& dem,
                                const std::string& release_path) {
    check_release_on_valid_dem(release.thickness, dem, release_path);
}

}  // namespace avalanche::gis
