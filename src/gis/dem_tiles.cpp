// Opening DEM tiles and planning the target grid (CRS, cell size, extent).
#include "dem_tiles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "crs_support.hpp"

namespace avalanche::gis::detail {

namespace {

constexpr int kScanRows = 256;            // rows per read while scanning a tile
constexpr int kScanStripValues = 1 << 22; // at most this many values per read
constexpr double kAlignTolerance = 1e-6;  // in cells: origins this close are "aligned"
constexpr int kDensifyPoints = 21;        // points per edge when reprojecting a bounding box
// Land elevations never reach this (m); values at or below it are void markers.
constexpr double kUndeclaredVoidBelow = -9999.0;

void scan_values(DemTile& tile) {
    GDALRasterBand* band = tile.ds->GetRasterBand(1);
    int has_nodata = 0;
    const double nodata = band->GetNoDataValue(&has_nodata);
    const int nx = tile.ds->GetRasterXSize(), ny = tile.ds->GetRasterYSize();
    // Fewer rows per strip for very wide rasters: the strip buffer stays ~32 MB.
    const int strip_rows = std::clamp(kScanStripValues / std::max(nx, 1), 1, kScanRows);
    std::vector<double> strip(static_cast<std::size_t>(nx) * strip_rows);
    tile.z_min = std::numeric_limits<double>::infinity();
    tile.z_max = -tile.z_min;
    for (int row = 0; row < ny; row += strip_rows) {
        const int rows = std::min(strip_rows, ny - row);
        if (band->RasterIO(GF_Read, 0, row, nx, rows, strip.data(), nx, rows, GDT_Float64, 0, 0,
                           nullptr) != CE_None)
            throw InputError(tile.path, "cannot read rows " + std::to_string(row) + "-" +
                                            std::to_string(row + rows - 1) +
                                            " (truncated or corrupt file?)");
        for (std::size_t k = 0; k < static_cast<std::size_t>(nx) * rows; ++k) {
            const double v = strip[k];
            if (!std::isfinite(v) || (has_nodata && v == nodata)) {
                ++tile.void_cells;
                continue;
            }
            ++tile.valid_cells;
            tile.z_min = std::min(tile.z_min, v);
            tile.z_max = std::max(tile.z_max, v);
        }
    }
}

std::array<double, 4> tile_bounds(const DemTile& t) {  // xmin, ymin, xmax, ymax
    const double w = t.ds->GetRasterXSize(), h = t.ds->GetRasterYSize();
    std::array<double, 4> b{
        std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (double p : {0.0, w})
        for (double l : {0.0, h}) {
            const double x = t.gt[0] + p * t.gt[1] + l * t.gt[2];
            const double y = t.gt[3] + p * t.gt[4] + l * t.gt[5];
            b = {std::min(b[0], x), std::min(b[1], y), std::max(b[2], x), std::max(b[3], y)};
        }
    return b;
}

std::array<double, 4> bounds_in(const DemTile& t, const OGRSpatialReference& target) {
    std::array<double, 4> b = tile_bounds(t);
    TransformPtr ct = make_transform(t.srs, target, t.path);
    std::array<double, 4> out{};
    if (!ct->TransformBounds(b[0], b[1], b[2], b[3], &out[0], &out[1], &out[2], &out[3],
                             kDensifyPoints))
        throw InputError(t.path, "cannot reproject the DEM extent to " + label_of(target));
    return out;
}

// Half a power of ten: 30.9 -> 30, 4.9977 -> 5, 0.93 -> 0.95.
double round_cell_size(double s) {
    const double step = std::pow(10.0, std::floor(std::log10(s))) / 2.0;
    return std::max(step, std::round(s / step) * step);
}

// Pixel spacing of the tile at its centre, in metres of the target CRS (coarser axis).
double metric_spacing(const DemTile& t, const OGRSpatialReference& target) {
    TransformPtr ct = make_transform(t.srs, target, t.path);
    const double p = t.ds->GetRasterXSize() / 2.0, l = t.ds->GetRasterYSize() / 2.0;
    double x[3], y[3];
    const double dp[3] = {0, 1, 0}, dl[3] = {0, 0, 1};
    for (int k = 0; k < 3; ++k) {
        x[k] = t.gt[0] + (p + dp[k]) * t.gt[1] + (l + dl[k]) * t.gt[2];
        y[k] = t.gt[3] + (p + dp[k]) * t.gt[4] + (l + dl[k]) * t.gt[5];
    }
    if (!ct->Transform(3, x, y))
        throw InputError(t.path, "cannot reproject the DEM centre to " + label_of(target));
    const double sx = std::hypot(x[1] - x[0], y[1] - y[0]);
    const double sy = std::hypot(x[2] - x[0], y[2] - y[0]);
    return round_cell_size(std::max(sx, sy));
}

void require_metric_projected(const OGRSpatialReference& srs, const std::string& what,
                              const std::string& key) {
    if (!srs.IsProjected())
        throw ConfigError(
            key, what + " " + label_of(srs) + " is not a projected CRS; the solver needs metres");
    const char* unit = nullptr;
    const double to_metre = srs.GetLinearUnits(&unit);
    if (std::abs(to_metre - 1.0) > 1e-12)
        throw ConfigError(key, what + " " + label_of(srs) + " uses " +
                                   (unit != nullptr ? unit : "?") +
                                   "; give a CRS in metres (e.g. the UTM zone)");
}

bool is_north_up(const std::array<double, 6>& gt) {
    return gt[2] == 0.0 && gt[4] == 0.0 && gt[1] > 0.0 && gt[5] < 0.0;
}

bool is_aligned(double offset, double step) {
    const double n = offset / step;
    return std::abs(n - std::round(n)) < kAlignTolerance;
}

}  // namespace

DemTile open_dem_tile(const std::string& path, const OGRSpatialReference& user_crs,
                      const GdalErrorScope& errors) {
    DemTile tile;
    tile.path = path;
    tile.ds = open_raster(path, errors);
    if (tile.ds->GetGeoTransform(tile.gt.data()) != CE_None)
        throw InputError(path, "has no georeferencing (no geotransform)");
    const OGRSpatialReference* srs = tile.ds->GetSpatialRef();
    if (srs != nullptr && !srs->IsEmpty()) {
        tile.srs = traditional(*srs);
    } else if (!user_crs.IsEmpty()) {
        tile.srs = user_crs;
    } else {
        throw InputError(path,
                         "has no coordinate reference system; give the DEM's CRS "
                         "(option crs, e.g. EPSG:31287)");
    }
    // Elevations stored scaled (integers in dm or cm, with a scale and offset in the
    // band's metadata): the warper and the readers take the stored values, so the
    // terrain would be ten or a hundred times too tall. Refused rather than unscaled
    // here, as the nodata value would have to be unscaled with them.
    GDALRasterBand* band = tile.ds->GetRasterBand(1);
    int has_scale = 0, has_offset = 0;
    const double scale = band->GetScale(&has_scale), offset = band->GetOffset(&has_offset);
    if ((has_scale && scale != 1.0) || (has_offset && offset != 0.0))
        throw InputError(path, "band 1 stores scaled elevations (scale " + std::to_string(scale) +
                                   ", offset " + std::to_string(offset) +
                                   "); expected elevations in m: convert it first, e.g. "
                                   "gdal_translate -unscale -ot Float32 in.tif out.tif");
    return tile;
}

void scan_dem_tile(DemTile& tile) {
    const std::string& path = tile.path;
    scan_values(tile);
    if (tile.valid_cells == 0)
        throw InputError(path, "contains no valid elevation (every cell is nodata or NaN)");
    int has_nodata = 0;
    tile.ds->GetRasterBand(1)->GetNoDataValue(&has_nodata);
    // Void markers (-9999, -32768, -3.4e38) in a file that does not declare them would
    // be interpolated into cliffs thousands of metres deep: refuse instead of guessing.
    if (!has_nodata && tile.z_min <= kUndeclaredVoidBelow)
        throw InputError(path, "has elevations of " + std::to_string(tile.z_min) +
                                   " m but declares no nodata value; declare the void "
                                   "marker (gdal_edit.py -a_nodata <value>)");
}

GridPlan plan_dem_grid(const std::vector<DemTile>& tiles, const OGRSpatialReference& user_crs,
                       const DemOptions& opts) {
    GridPlan plan;
    const DemTile& first = tiles.front();
    OGRSpatialReference target;
    if (!user_crs.IsEmpty()) {
        target = user_crs;
        plan.crs_reason = "the requested CRS";
    } else if (first.srs.IsGeographic()) {
        OGRSpatialReference wgs84;
        wgs84.importFromEPSG(4326);
        wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        double lon0 = 1e300, lat0 = 1e300, lon1 = -1e300, lat1 = -1e300;
        for (const DemTile& t : tiles) {
            const auto b = bounds_in(t, wgs84);
            lon0 = std::min(lon0, b[0]), lat0 = std::min(lat0, b[1]);
            lon1 = std::max(lon1, b[2]), lat1 = std::max(lat1, b[3]);
        }
        target = srs_from_text(utm_crs_wkt_for((lon0 + lon1) / 2, (lat0 + lat1) / 2), "crs");
        plan.crs_reason = "the UTM zone of the DEM centre (geographic DEM)";
    } else {
        target = first.srs;
        plan.crs_reason = "the DEM's own CRS";
    }
    require_metric_projected(target, user_crs.IsEmpty() ? "the DEM CRS" : "the requested CRS",
                             "crs");
    target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);

    // Cell size and anchor: keep the first tile's cells when it is already in the target
    // CRS, so a projected DEM is not resampled at all.
    const bool first_native = first.srs.IsSame(&target) && is_north_up(first.gt);
    double dx = opts.cell_size, dy = opts.cell_size;
    if (dx == 0.0) {
        if (first_native) {
            dx = first.gt[1], dy = -first.gt[5];
        } else {
            dx = dy = metric_spacing(first, target);
        }
        dx *= opts.cell_size_factor;
        dy *= opts.cell_size_factor;
    }
    const double anchor_x = first_native ? first.gt[0] : 0.0;
    const double anchor_y = first_native ? first.gt[3] : 0.0;

    double x_min = 1e300, y_min = 1e300, x_max = -1e300, y_max = -1e300;
    plan.same_as_source = true;
    for (const DemTile& t : tiles) {
        const auto b = t.srs.IsSame(&target) ? tile_bounds(t) : bounds_in(t, target);
        x_min = std::min(x_min, b[0]), y_min = std::min(y_min, b[1]);
        x_max = std::max(x_max, b[2]), y_max = std::max(y_max, b[3]);
        plan.same_as_source =
            plan.same_as_source && t.srs.IsSame(&target) && is_north_up(t.gt) &&
            std::abs(t.gt[1] - dx) < 1e-9 * dx && std::abs(-t.gt[5] - dy) < 1e-9 * dy &&
            is_aligned(t.gt[0] - anchor_x, dx) && is_aligned(t.gt[3] - anchor_y, dy);
    }
    // Snap the union extent outwards onto the anchor's lattice.
    const double left = anchor_x + std::floor((x_min - anchor_x) / dx + kAlignTolerance) * dx;
    const double right = anchor_x + std::ceil((x_max - anchor_x) / dx - kAlignTolerance) * dx;
    const double bottom = anchor_y + std::floor((y_min - anchor_y) / dy + kAlignTolerance) * dy;
    const double top = anchor_y + std::ceil((y_max - anchor_y) / dy - kAlignTolerance) * dy;
    const double nx = std::round((right - left) / dx), ny = std::round((top - bottom) / dy);

    // The memory estimate, before anything of the grid's size is allocated or read (a
    // header can declare 200000 x 200000 cells in a few hundred bytes). The DEM is
    // named: it is the input that does not fit (or the cell size asked of it).
    const double cells = nx * ny;
    const double bytes = cells * opts.solver_bytes_per_cell;
    if (bytes > opts.max_solver_bytes || nx > std::numeric_limits<int>::max() / 2 ||
        ny > std::numeric_limits<int>::max() / 2) {
        std::ostringstream msg;
        msg.precision(3);
        msg << "a " << static_cast<long long>(nx) << " x " << static_cast<long long>(ny)
            << " grid of " << dx << " m cells (cell_size) needs about "
            << bytes / (1u << 30) << " GiB of solver state (" << opts.solver_bytes_per_cell
            << " B per cell), above the " << opts.max_solver_bytes / (1u << 30) << " GiB of "
            << opts.memory_limit_source << "; choose a larger cell size or crop the DEM";
        std::string files;
        for (const DemTile& t : tiles) files += (files.empty() ? "" : ", ") + t.path;
        throw InputError(files, msg.str());
    }
    plan.geo.grid = Grid{static_cast<int>(nx), static_cast<int>(ny), dx, dy, left, bottom};
    plan.geo.crs_wkt = to_wkt(target);
    return plan;
}

}  // namespace avalanche::gis::detail

namespace avalanche::gis {

void check_grid_crs(const std::string& text, const std::string& key) {
    detail::require_metric_projected(detail::srs_from_text(text, key), "the requested CRS", key);
}

}  // namespace avalanche::gis
