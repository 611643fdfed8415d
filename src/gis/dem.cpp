// load_dem: tiles -> checked -> one metric grid (GDALWarp) -> voids filled and counted.
#include "avalanche/gis/dem.hpp"

#include <gdal_utils.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "crs_support.hpp"
#include "dem_tiles.hpp"
#include "orientation.hpp"
#include "void_fill.hpp"
#include "warp.hpp"

namespace avalanche::gis {

namespace {

void check_options(const DemOptions& opts) {
    if (!std::isfinite(opts.cell_size) || opts.cell_size < 0.0)
        throw ConfigError("cell_size", "expected a positive cell size in metres (0 = the DEM's)");
    if (!(opts.max_solver_bytes > 0.0) || !(opts.solver_bytes_per_cell > 0.0))
        throw ConfigError("max_solver_bytes", "expected positive memory limits");
}

std::string join(const std::vector<std::string>& paths) {
    std::string out;
    for (const auto& p : paths) out += (out.empty() ? "" : ", ") + p;
    return out;
}

std::string describe(const std::vector<detail::DemTile>& tiles, const detail::GridPlan& plan,
                     const std::string& resampling, const Dem& dem) {
    std::ostringstream s;
    s.precision(10);
    long long source_voids = 0;
    for (const auto& t : tiles) source_voids += t.void_cells;
    s << "Read " << tiles.size() << (tiles.size() == 1 ? " DEM file" : " DEM tiles") << " ("
      << detail::label_of(tiles.front().srs) << ", " << source_voids << " void source cells). ";
    if (plan.same_as_source)
        s << "Kept the source cells (no resampling) in " << dem.geo.crs_label() << ". ";
    else
        s << "Warped to " << dem.geo.crs_label() << " (" << plan.crs_reason << ") with "
          << resampling << " resampling. ";
    s << "Grid " << dem.geo.grid.nx << " x " << dem.geo.grid.ny << " cells of " << dem.geo.grid.dx
      << " x " << dem.geo.grid.dy << " m, west edge " << dem.geo.grid.x0 << ", south edge "
      << dem.geo.grid.y0 << ". Elevation " << dem.z_min << " to " << dem.z_max << " m. Filled "
      << dem.filled_voids << " void cells (" << dem.filled_holes << " enclosed holes, "
      << dem.filled_outside
      << " outside the data footprint) by inverse-distance interpolation (GDALFillNodata).";
    return s.str();
}

// The datasets made on the way to the warp (CRS views, Float64 views, mosaics), each
// reading those made before it: closed newest first. (A vector closes its elements
// oldest first; a mosaic then flushed into views already closed and crashed.)
struct MadeDatasets {
    std::vector<detail::DatasetPtr> list;
    MadeDatasets() = default;
    MadeDatasets(const MadeDatasets&) = delete;
    MadeDatasets& operator=(const MadeDatasets&) = delete;
    ~MadeDatasets() {
        while (!list.empty()) list.pop_back();
    }
};

// A tile without a CRS in its file gets the user's CRS through a VRT view, so that
// the warper knows it too (GDALWarp reads the CRS from the dataset).
GDALDataset* with_crs(detail::DemTile& t, std::vector<detail::DatasetPtr>& owned,
                      const detail::GdalErrorScope& errors) {
    const OGRSpatialReference* own = t.ds->GetSpatialRef();
    if (own != nullptr && !own->IsEmpty()) return t.ds.get();
    GDALDriver* vrt = GetGDALDriverManager()->GetDriverByName("VRT");
    detail::DatasetPtr view(vrt->CreateCopy("", t.ds.get(), FALSE, nullptr, nullptr, nullptr));
    if (!view) throw InputError(t.path, "cannot attach the CRS" + errors.reason());
    view->SetSpatialRef(&t.srs);
    owned.push_back(std::move(view));
    return owned.back().get();
}

// Whether the tiles' first bands share a data type, as GDALBuildVRT requires.
bool same_data_type(const std::vector<GDALDatasetH>& members) {
    const auto type_of = [](GDALDatasetH h) {
        return GDALGetRasterDataType(GDALGetRasterBand(h, 1));
    };
    return std::all_of(members.begin(), members.end(),
                       [&](GDALDatasetH h) { return type_of(h) == type_of(members.front()); });
}

// Replaces each tile by a Float64 view of it (a VRT: nothing is copied), so that tiles
// stored in different types (Int16 beside Float32, say) mosaic together; every
// elevation of those types is exact in a double.
void as_float64(std::vector<GDALDatasetH>& members, const std::vector<std::string>& names,
                std::vector<detail::DatasetPtr>& owned, const detail::GdalErrorScope& errors) {
    const char* args[] = {"-of", "VRT", "-ot", "Float64", nullptr};
    GDALTranslateOptions* options = GDALTranslateOptionsNew(const_cast<char**>(args), nullptr);
    for (std::size_t k = 0; k < members.size(); ++k) {
        int usage_error = 0;
        detail::DatasetPtr view(
            GDALDataset::FromHandle(GDALTranslate("", members[k], options, &usage_error)));
        if (!view || usage_error) {
            GDALTranslateOptionsFree(options);
            throw InputError(names[k], "cannot read it as Float64" + errors.reason());
        }
        members[k] = GDALDataset::ToHandle(view.get());
        owned.push_back(std::move(view));
    }
    GDALTranslateOptionsFree(options);
}

// Tiles sharing a CRS are mosaicked first (GDALBuildVRT), so that the warper
// interpolates across their seams as within one file; only mosaics in different CRSs
// are warped one after the other.
std::vector<GDALDataset*> mosaic_by_crs(std::vector<detail::DemTile>& tiles,
                                        std::vector<detail::DatasetPtr>& owned,
                                        const detail::GdalErrorScope& errors) {
    std::vector<std::vector<std::size_t>> groups;
    for (std::size_t k = 0; k < tiles.size(); ++k) {
        auto same = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
            return tiles[g.front()].srs.IsSame(&tiles[k].srs);
        });
        if (same == groups.end())
            groups.push_back({k});
        else
            same->push_back(k);
    }
    std::vector<GDALDataset*> sources;
    for (const auto& group : groups) {
        std::vector<GDALDatasetH> members;
        std::vector<std::string> names;
        for (std::size_t k : group) {
            members.push_back(GDALDataset::ToHandle(with_crs(tiles[k], owned, errors)));
            names.push_back(tiles[k].path);
        }
        if (members.size() == 1) {
            sources.push_back(GDALDataset::FromHandle(members.front()));
            continue;
        }
        if (!same_data_type(members)) as_float64(members, names, owned, errors);
        const char* args[] = {"-resolution", "highest", nullptr};
        GDALBuildVRTOptions* options = GDALBuildVRTOptionsNew(const_cast<char**>(args), nullptr);
        int usage_error = 0;
        const std::size_t warnings_before = errors.warnings().size();
        detail::DatasetPtr vrt(GDALDataset::FromHandle(GDALBuildVRT(
            "", static_cast<int>(members.size()), members.data(), nullptr, options, &usage_error)));
        GDALBuildVRTOptionsFree(options);
        if (!vrt || usage_error)
            throw InputError(join(names), "cannot mosaic these tiles" + errors.reason());
        // GDALBuildVRT leaves out, with a mere warning, a tile it cannot take.
        for (std::size_t k = warnings_before; k < errors.warnings().size(); ++k)
            if (detail::lower(errors.warnings()[k]).find("skipping") != std::string::npos)
                throw InputError(join(names), "cannot mosaic these tiles: " + errors.warnings()[k]);
        owned.push_back(std::move(vrt));
        sources.push_back(owned.back().get());
    }
    return sources;
}

}  // namespace

Dem load_dem(const std::vector<std::string>& paths, const DemOptions& opts) {
    detail::GdalErrorScope errors;
    if (paths.empty()) throw ConfigError("dem", "no DEM file given");
    check_options(opts);
    std::string resampling = detail::gdal_resampling(opts.resampling, "resampling");
    const OGRSpatialReference user_crs = detail::srs_from_text(opts.crs, "crs");

    std::vector<detail::DemTile> tiles;
    for (const auto& path : paths) tiles.push_back(detail::open_dem_tile(path, user_crs, errors));
    const detail::GridPlan plan = detail::plan_dem_grid(tiles, user_crs, opts);
    for (auto& tile : tiles) detail::scan_dem_tile(tile);  // only once the grid fits
    if (plan.same_as_source) resampling = "near";  // exact copy of the source cells

    MadeDatasets made;
    const std::vector<GDALDataset*> sources = mosaic_by_crs(tiles, made.list, errors);
    detail::DatasetPtr warped =
        detail::warp_onto_grid(sources, plan.geo, resampling, join(paths), errors, opts.threads);

    Dem dem;
    dem.geo = plan.geo;
    dem.z = detail::read_solver_rows(*warped, 1, dem.geo.grid, join(paths));
    warped.reset();
    const auto measured =
        std::count_if(dem.z.begin(), dem.z.end(), [](double v) { return std::isfinite(v); });
    if (measured == 0) throw InputError(join(paths), "no valid elevation falls on the grid");
    dem.z_min = 1e300, dem.z_max = -1e300;
    for (double v : dem.z)
        if (std::isfinite(v))
            dem.z_min = std::min(dem.z_min, v), dem.z_max = std::max(dem.z_max, v);

    detail::VoidFillResult voids = detail::fill_voids(dem.geo, dem.z, opts.threads);
    dem.filled_holes = voids.holes;
    dem.filled_outside = voids.outside;
    dem.filled_voids = voids.holes + voids.outside;
    dem.filled_mask = std::move(voids.origin);
    dem.description_of_steps = describe(tiles, plan, resampling, dem);
    return dem;
}

void write_dem(const std::string& path, const Dem& dem) {
    // nodata is declared for QGIS but never present: every void is filled.
    BandInfo band{"elevation of the computational grid", "m", -9999.0, {}, {}};
    band.metadata["FILLED_VOIDS"] = std::to_string(dem.filled_voids);
    band.metadata["FILLED_HOLES"] = std::to_string(dem.filled_holes);
    band.metadata["FILLED_OUTSIDE_FOOTPRINT"] = std::to_string(dem.filled_outside);
    band.metadata["PROCESSING"] = dem.description_of_steps;
    write_geotiff(path, dem.geo, dem.z, band, SampleType::float32);
}

}  // namespace avalanche::gis
