// COG GeoTIFF writer: MEM dataset in GDAL orientation -> COG driver CreateCopy.
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/raster_writer.hpp"
#include "orientation.hpp"

namespace avalanche::gis {

namespace {

struct TypeInfo {
    GDALDataType gdal;
    bool integer;
    double lowest, highest;
};

TypeInfo type_info(SampleType t) {
    const double inf = std::numeric_limits<double>::infinity();
    switch (t) {
        case SampleType::float32:
            return {GDT_Float32, false, -3.4028234663852886e38, 3.4028234663852886e38};
        case SampleType::float64:
            return {GDT_Float64, false, -inf, inf};
        case SampleType::int16:
            return {GDT_Int16, true, -32768, 32767};
        case SampleType::int32:
            return {GDT_Int32, true, -2147483648.0, 2147483647.0};
        case SampleType::uint8:
            return {GDT_Byte, true, 0, 255};
        case SampleType::uint16:
            return {GDT_UInt16, true, 0, 65535};
    }
    return {GDT_Float32, false, -inf, inf};
}

// Every value must be representable: never write NaN, never let GDAL clamp silently.
void check_values(const std::string& path, const GeoGrid& geo, const std::vector<double>& values,
                  const TypeInfo& type, double nodata) {
    if (values.size() != geo.grid.cells())
        throw OutputError(path, "has " + std::to_string(values.size()) + " values for a " +
                                    std::to_string(geo.grid.nx) + " x " +
                                    std::to_string(geo.grid.ny) + " grid");
    auto fail = [&](std::size_t k, const std::string& what) {
        const int i = static_cast<int>(k % geo.grid.nx), j = static_cast<int>(k / geo.grid.nx);
        std::ostringstream msg;
        msg << what << " at cell (i=" << i << ", j=" << j << "), x=" << geo.grid.x_center(i)
            << ", y=" << geo.grid.y_center(j) << "; refusing to write it";
        throw OutputError(path, msg.str());
    };
    if (!std::isfinite(nodata) || nodata < type.lowest || nodata > type.highest ||
        (type.integer && nodata != std::round(nodata)))
        throw OutputError(
            path, "nodata value " + std::to_string(nodata) + " does not fit the sample type");
    for (std::size_t k = 0; k < values.size(); ++k) {
        const double v = values[k];
        if (!std::isfinite(v)) fail(k, "non-finite value (" + std::to_string(v) + ")");
        if (v < type.lowest || v > type.highest)
            fail(k, "value " + std::to_string(v) + " out of the sample type's range");
        if (type.integer && v != std::round(v))
            fail(k, "non-integer value " + std::to_string(v) + " for an integer raster");
    }
}

// GDAL_PAM_ENABLED=NO for this thread while writing: everything must go into the TIFF
// itself, no ".aux.xml" sidecar that would be left behind by the rename.
class NoPamScope {
  public:
    NoPamScope() {
        const char* old = CPLGetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr);
        had_ = old != nullptr;
        if (had_) old_ = old;
        CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO");
    }
    ~NoPamScope() {
        CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", had_ ? old_.c_str() : nullptr);
    }
    NoPamScope(const NoPamScope&) = delete;
    NoPamScope& operator=(const NoPamScope&) = delete;

  private:
    bool had_ = false;
    std::string old_;
};

}  // namespace

void write_geotiff(const std::string& path, const GeoGrid& geo, const std::vector<double>& values,
                   const BandInfo& band, SampleType type, Predictor predictor) {
    detail::GdalErrorScope errors;
    NoPamScope no_pam;
    const TypeInfo info = type_info(type);
    check_values(path, geo, values, info, band.nodata);
    const std::filesystem::path target(path);
    const auto folder =
        target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
    std::error_code ec;
    if (!std::filesystem::is_directory(folder, ec))
        throw OutputError(path, "folder " + folder.string() + " does not exist");

    detail::DatasetPtr mem = detail::mem_from_solver_rows(geo, values, info.gdal);
    GDALRasterBand* b = mem->GetRasterBand(1);
    b->SetNoDataValue(band.nodata);
    b->SetDescription(band.description.c_str());
    b->SetUnitType(band.units.c_str());
    for (const auto& [key, value] : band.metadata) b->SetMetadataItem(key.c_str(), value.c_str());
    for (const auto& [key, value] : band.dataset_metadata) mem->SetMetadataItem(key.c_str(), value.c_str());

    GDALDriver* cog = GetGDALDriverManager()->GetDriverByName("COG");
    if (cog == nullptr) throw OutputError(path, "GDAL has no COG driver (GDAL >= 3.1 needed)");
    CPLStringList options;
    options.SetNameValue("COMPRESS", "DEFLATE");
    // YES: 2 for integers, 3 for floats.
    options.SetNameValue("PREDICTOR", predictor == Predictor::automatic ? "YES" : "NO");
    options.SetNameValue("OVERVIEWS", "AUTO");
    options.SetNameValue("OVERVIEW_RESAMPLING", info.integer ? "NEAREST" : "AVERAGE");

    const std::string part = path + ".part";
    std::filesystem::remove(part, ec);
    bool written = false;
    {
        detail::DatasetPtr out(
            cog->CreateCopy(part.c_str(), mem.get(), FALSE, options.List(), nullptr, nullptr));
        written = out != nullptr;
    }  // closes the file: the last bytes reach the disk here (failures land in `errors`)
    if (!written || errors.failed()) {
        std::filesystem::remove(part, ec);
        throw OutputError(path, "cannot write the GeoTIFF" + errors.reason());
    }
    std::filesystem::rename(part, target, ec);
    if (ec) {
        const std::string why = ec.message();
        std::filesystem::remove(part, ec);
        throw OutputError(path, "cannot rename " + part + " into place: " + why);
    }
}

}  // namespace avalanche::gis
