#pragma once
// Helpers of the DEM pipeline tests: fixtures derived from the bundled avaKot scene with
// GDAL's own utilities (the library functions behind gdalwarp, gdal_translate and
// ogr2ogr, so no shell quoting and no PATH lookup), and product rasters read back with
// plain GDAL, independently of the code under test.
#include <cpl_string.h>
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <array>
#include <cmath>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace avalanche::test {

inline std::string avaKot(const std::string& file) {
    return std::string(AVALANCHE_SOURCE_DIR) + "/dem/avaKot/" + file;
}

inline nlohmann::json read_json_file(const std::string& path) {
    std::ifstream f(path);
    return nlohmann::json::parse(f);
}

// `args` as on the command line of the tool, e.g. {"-tr", "20", "20"}.
inline CPLStringList string_list(const std::vector<std::string>& args) {
    CPLStringList list;
    for (const auto& a : args) list.AddString(a.c_str());
    return list;
}

// gdalwarp src dst args...
inline bool gdal_warp(const std::string& src, const std::string& dst,
                      const std::vector<std::string>& args) {
    GDALAllRegister();
    GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
    if (in == nullptr) return false;
    CPLStringList argv = string_list(args);
    GDALWarpAppOptions* opts = GDALWarpAppOptionsNew(argv.List(), nullptr);
    int usage_error = 0;
    GDALDatasetH out = GDALWarp(dst.c_str(), nullptr, 1, &in, opts, &usage_error);
    GDALWarpAppOptionsFree(opts);
    GDALClose(in);
    if (out != nullptr) GDALClose(out);
    return out != nullptr && usage_error == 0;
}

// gdal_translate src dst args...
inline bool gdal_translate(const std::string& src, const std::string& dst,
                           const std::vector<std::string>& args) {
    GDALAllRegister();
    GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
    if (in == nullptr) return false;
    CPLStringList argv = string_list(args);
    GDALTranslateOptions* opts = GDALTranslateOptionsNew(argv.List(), nullptr);
    int usage_error = 0;
    GDALDatasetH out = GDALTranslate(dst.c_str(), in, opts, &usage_error);
    GDALTranslateOptionsFree(opts);
    GDALClose(in);
    if (out != nullptr) GDALClose(out);
    return out != nullptr && usage_error == 0;
}

// ogr2ogr dst src args...
inline bool ogr2ogr(const std::string& dst, const std::string& src,
                    const std::vector<std::string>& args) {
    GDALAllRegister();
    GDALDatasetH in = GDALOpenEx(src.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
    if (in == nullptr) return false;
    CPLStringList argv = string_list(args);
    GDALVectorTranslateOptions* opts = GDALVectorTranslateOptionsNew(argv.List(), nullptr);
    int usage_error = 0;
    GDALDatasetH out = GDALVectorTranslate(dst.c_str(), nullptr, 1, &in, opts, &usage_error);
    GDALVectorTranslateOptionsFree(opts);
    GDALClose(in);
    if (out != nullptr) GDALClose(out);
    return out != nullptr && usage_error == 0;
}

// A product raster as GDAL sees it: row 0 is the top of the file.
struct Raster {
    int width = 0, height = 0;
    std::array<double, 6> gt{};
    bool has_nodata = false;
    double nodata = 0.0;
    std::string epsg;  // authority code of the CRS, "" if none
    std::vector<double> values;

    [[nodiscard]] double at(int col, int row) const {
        return values[static_cast<std::size_t>(row) * width + col];
    }
    [[nodiscard]] bool valid(int col, int row) const {
        const double v = at(col, row);
        return !(has_nodata && v == nodata);
    }
    // Cell holding the map point (x, y); false outside the raster.
    bool cell_of(double x, double y, int& col, int& row) const {
        col = static_cast<int>(std::floor((x - gt[0]) / gt[1]));
        row = static_cast<int>(std::floor((y - gt[3]) / gt[5]));
        return col >= 0 && col < width && row >= 0 && row < height;
    }
    [[nodiscard]] std::array<double, 2> centre(int col, int row) const {
        return {gt[0] + (col + 0.5) * gt[1], gt[3] + (row + 0.5) * gt[5]};
    }
};

inline Raster read_raster(const std::string& path) {
    GDALAllRegister();
    Raster r;
    GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    EXPECT_NE(ds, nullptr) << path;
    if (ds == nullptr) return r;
    r.width = ds->GetRasterXSize();
    r.height = ds->GetRasterYSize();
    EXPECT_EQ(ds->GetGeoTransform(r.gt.data()), CE_None) << path;
    if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
        const char* code = srs->GetAuthorityCode(nullptr);
        if (code != nullptr) r.epsg = code;
    }
    GDALRasterBand* band = ds->GetRasterBand(1);
    int has = 0;
    r.nodata = band->GetNoDataValue(&has);
    r.has_nodata = has != 0;
    r.values.resize(static_cast<std::size_t>(r.width) * r.height);
    EXPECT_EQ(band->RasterIO(GF_Read, 0, 0, r.width, r.height, r.values.data(), r.width, r.height,
                             GDT_Float64, 0, 0, nullptr),
              CE_None)
        << path;
    GDALClose(ds);
    return r;
}

// The first polygon of a vector file, reprojected to `epsg` (traditional x/y order) unless
// epsg is 0.
inline std::unique_ptr<OGRGeometry> first_polygon(const std::string& path, int epsg = 0) {
    GDALAllRegister();
    auto* ds = static_cast<GDALDataset*>(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
    EXPECT_NE(ds, nullptr) << path;
    if (ds == nullptr) return nullptr;
    OGRLayer* layer = ds->GetLayer(0);
    OGRFeature* f = layer->GetNextFeature();
    std::unique_ptr<OGRGeometry> g(f->GetGeometryRef()->clone());
    OGRFeature::DestroyFeature(f);
    if (epsg == 0) {
        GDALClose(ds);
        return g;
    }
    OGRSpatialReference target;
    target.importFromEPSG(epsg);
    target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference source(*layer->GetSpatialRef());
    source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    g->assignSpatialReference(&source);
    EXPECT_EQ(g->transformTo(&target), OGRERR_NONE);
    g->assignSpatialReference(nullptr);  // both references are locals
    GDALClose(ds);
    return g;
}

}  // namespace avalanche::test
