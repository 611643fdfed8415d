#include "gdal_support.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <mutex>

#include "avalanche/core/error.hpp"

namespace avalanche::gis::detail {

void ensure_gdal_registered() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

GdalErrorScope::GdalErrorScope() {
    ensure_gdal_registered();
    CPLPushErrorHandlerEx(&GdalErrorScope::handler, this);
}

GdalErrorScope::~GdalErrorScope() { CPLPopErrorHandler(); }

void CPL_STDCALL GdalErrorScope::handler(CPLErr level, CPLErrorNum /*number*/,
                                         const char* message) {
    auto* self = static_cast<GdalErrorScope*>(CPLGetErrorHandlerUserData());
    if (self == nullptr || level == CE_Debug || level == CE_None) return;
    const std::string text = message != nullptr ? message : "";
    if (level == CE_Warning)
        self->warnings_.push_back(text);
    else
        self->failures_.push_back(text);
}

std::string GdalErrorScope::reason() const {
    if (failures_.empty()) return "";
    return " (GDAL: " + failures_.front() + ")";
}

void GdalErrorScope::clear() {
    failures_.clear();
    warnings_.clear();
}

namespace {
void require_existing_file(const std::string& path) {
    std::error_code ec;
    // "/vsi..." paths (zip, curl, memory) are GDAL virtual files: let GDAL judge them.
    if (path.rfind("/vsi", 0) == 0) return;
    if (!std::filesystem::exists(path, ec)) throw InputError(path, "file not found");
}
}  // namespace

DatasetPtr open_raster(const std::string& path, const GdalErrorScope& errors) {
    require_existing_file(path);
    DatasetPtr ds(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR, nullptr,
                   nullptr, nullptr)));
    if (!ds) throw InputError(path, "not a readable raster file" + errors.reason());
    if (ds->GetRasterCount() < 1) throw InputError(path, "raster has no band");
    return ds;
}

DatasetPtr open_vector(const std::string& path, const GdalErrorScope& errors) {
    require_existing_file(path);
    DatasetPtr ds(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR, nullptr,
                   nullptr, nullptr)));
    if (!ds) throw InputError(path, "not a readable vector file" + errors.reason());
    return ds;
}

std::vector<OGRLayer*> geometry_layers(GDALDataset& ds) {
    std::vector<OGRLayer*> layers;
    for (OGRLayer* layer : ds.GetLayers())
        if (layer->GetLayerDefn()->GetGeomFieldCount() > 0) layers.push_back(layer);
    return layers;
}

std::unique_ptr<OGRGeometry> linear_copy(const OGRGeometry& g) {
    return std::unique_ptr<OGRGeometry>(g.hasCurveGeometry() ? g.getLinearGeometry() : g.clone());
}

DatasetPtr create_mem_raster(int width, int height, int bands, GDALDataType type) {
    ensure_gdal_registered();
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    if (mem == nullptr) throw Error(ExitCode::internal, "GDAL MEM driver is missing");
    DatasetPtr ds(mem->Create("", width, height, bands, type, nullptr));
    if (!ds) {
        throw Error(ExitCode::internal, "cannot allocate an in-memory raster of " +
                                            std::to_string(width) + " x " + std::to_string(height) +
                                            " cells");
    }
    return ds;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

}  // namespace avalanche::gis::detail
