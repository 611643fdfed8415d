#include "warp.hpp"

#include <gdal_utils.h>

#include <algorithm>
#include <array>
#include <limits>

#include "avalanche/core/error.hpp"
#include "orientation.hpp"

namespace avalanche::gis::detail {

namespace {
// Maximum error of the approximate warp transformer, in pixels. GDAL's default 0.125
// is 0.6 m on a 5 m grid, i.e. 0.6 m of elevation on a 45 degree slope; 0.01 costs
// little and keeps the interpolation points where the grid says they are.
constexpr const char* kWarpErrorThreshold = "0.01";
}  // namespace

std::string gdal_resampling(const std::string& name, const std::string& key) {
    static const std::array<std::array<const char*, 2>, 7> known{{{"nearest", "near"},
                                                                  {"near", "near"},
                                                                  {"bilinear", "bilinear"},
                                                                  {"cubic", "cubic"},
                                                                  {"cubicspline", "cubicspline"},
                                                                  {"lanczos", "lanczos"},
                                                                  {"average", "average"}}};
    const std::string wanted = lower(name);
    for (const auto& k : known)
        if (wanted == k[0]) return k[1];
    throw ConfigError(key, "unknown resampling '" + name +
                               "'; expected nearest, bilinear, cubic, cubicspline, lanczos or "
                               "average");
}

DatasetPtr warp_onto_grid(const std::vector<GDALDataset*>& sources, const GeoGrid& geo,
                          const std::string& resampling, const std::string& label,
                          GdalErrorScope& errors, int threads) {
    DatasetPtr dst = mem_for_grid(geo, 1, GDT_Float64);
    GDALRasterBand* band = dst->GetRasterBand(1);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    band->SetNoDataValue(nan);
    band->Fill(nan);

    // No INIT_DEST: the band is pre-filled with NaN above, and INIT_DEST would be applied
    // again for every source, erasing what the previous sources wrote.
    CPLStringList args;
    const std::string num_threads = "NUM_THREADS=" + std::to_string(std::max(1, threads));
    for (const char* a : {"-r", resampling.c_str(), "-et", kWarpErrorThreshold, "-q", "-wo", num_threads.c_str()})
        args.AddString(a);
    GDALWarpAppOptions* options = GDALWarpAppOptionsNew(args.List(), nullptr);
    std::vector<GDALDatasetH> handles;
    for (GDALDataset* s : sources) handles.push_back(GDALDataset::ToHandle(s));
    int usage_error = 0;
    GDALDatasetH out =
        GDALWarp(nullptr, GDALDataset::ToHandle(dst.get()), static_cast<int>(handles.size()),
                 handles.data(), options, &usage_error);
    GDALWarpAppOptionsFree(options);
    if (out == nullptr || usage_error || errors.failed())
        throw InputError(label, "cannot resample onto the " + std::to_string(geo.grid.nx) + " x " +
                                    std::to_string(geo.grid.ny) + " grid" + errors.reason());
    return dst;
}

}  // namespace avalanche::gis::detail
