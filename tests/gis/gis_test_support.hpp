#pragma once
// Helpers for the GIS tests. Fixtures are written with the raw GDAL API, in GDAL's
// own orientation (row 0 = north), independently of the library under test.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace avalanche::gis::testing {

inline std::string avaKot(const std::string& file) {
    return std::string(AVALANCHE_SOURCE_DIR) + "/dem/avaKot/" + file;
}
inline std::string fixture(const std::string& file) {
    return std::string(AVALANCHE_TEST_DATA_DIR) + "/gis/" + file;
}

// A fresh folder per test, removed afterwards.
class TempDir {
  public:
    TempDir() {
        static std::atomic<int> counter{0};
        path_ = std::filesystem::temp_directory_path() /
                ("avalanche_gis_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    [[nodiscard]] std::string file(const std::string& name) const {
        return (path_ / name).string();
    }

  private:
    std::filesystem::path path_;
};

// Writes a north-up GeoTIFF; value(col, row) with row 0 = the northern row.
inline void write_raw_geotiff(const std::string& path, int width, int height,
                              std::array<double, 6> gt, const std::string& srs_text,
                              const std::function<double(int, int)>& value,
                              GDALDataType type = GDT_Float32,
                              std::optional<double> nodata = std::nullopt) {
    GDALAllRegister();
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDataset* ds = gtiff->Create(path.c_str(), width, height, 1, type, nullptr);
    ASSERT_NE(ds, nullptr);
    ds->SetGeoTransform(gt.data());
    if (!srs_text.empty()) {
        OGRSpatialReference srs;
        srs.SetFromUserInput(srs_text.c_str());
        ds->SetSpatialRef(&srs);
    }
    if (nodata) ds->GetRasterBand(1)->SetNoDataValue(*nodata);
    std::vector<double> rows(static_cast<std::size_t>(width) * height);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c) rows[static_cast<std::size_t>(r) * width + c] = value(c, r);
    EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, width, height, rows.data(), width,
                                             height, GDT_Float64, 0, 0, nullptr),
              CE_None);
    GDALClose(ds);
}

// All values of band 1, GDAL orientation (row 0 = north).
inline std::vector<double> read_raw_rows(const std::string& path, int* width = nullptr,
                                         int* height = nullptr) {
    GDALAllRegister();
    GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER);
    EXPECT_NE(ds, nullptr) << path;
    if (ds == nullptr) return {};
    const int w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
    std::vector<double> rows(static_cast<std::size_t>(w) * h);
    EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, rows.data(), w, h, GDT_Float64, 0,
                                             0, nullptr),
              CE_None);
    GDALClose(ds);
    if (width) *width = w;
    if (height) *height = h;
    return rows;
}

// Copies the features of `source`'s first layer into a new GeoPackage `path` (layer
// "copied", the source's CRS and fields), each geometry forced to `type` (a curve type
// such as wkbCurvePolygon or wkbMultiSurface, or the source's own); with
// `attribute_table`, an attribute-only table beside it, as QGIS writes 'layer_styles'
// when a style is saved in the GeoPackage.
inline void copy_to_geopackage(const std::string& source, const std::string& path,
                               OGRwkbGeometryType type, bool attribute_table) {
    GDALAllRegister();
    GDALDataset* in = GDALDataset::Open(source.c_str(), GDAL_OF_VECTOR);
    ASSERT_NE(in, nullptr) << source;
    OGRLayer* from = in->GetLayer(0);
    GDALDriver* gpkg = GetGDALDriverManager()->GetDriverByName("GPKG");
    GDALDataset* out = gpkg->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
    ASSERT_NE(out, nullptr) << path;
    OGRLayer* to = out->CreateLayer("copied", from->GetSpatialRef(), type, nullptr);
    ASSERT_NE(to, nullptr);
    for (int k = 0; k < from->GetLayerDefn()->GetFieldCount(); ++k)
        ASSERT_EQ(to->CreateField(from->GetLayerDefn()->GetFieldDefn(k)), OGRERR_NONE);
    from->ResetReading();
    for (auto& f : *from) {
        OGRFeature copy(to->GetLayerDefn());
        ASSERT_EQ(copy.SetFrom(f.get()), OGRERR_NONE);
        copy.SetGeometryDirectly(
            OGRGeometryFactory::forceTo(f->GetGeometryRef()->clone(), type, nullptr));
        ASSERT_EQ(wkbFlatten(copy.GetGeometryRef()->getGeometryType()), wkbFlatten(type));
        ASSERT_EQ(to->CreateFeature(&copy), OGRERR_NONE);
    }
    if (attribute_table) {
        OGRLayer* table = out->CreateLayer("layer_styles", nullptr, wkbNone, nullptr);
        ASSERT_NE(table, nullptr);
        OGRFieldDefn name("styleName", OFTString);
        ASSERT_EQ(table->CreateField(&name), OGRERR_NONE);
        OGRFeature row(table->GetLayerDefn());
        row.SetField("styleName", "hazard");
        ASSERT_EQ(table->CreateFeature(&row), OGRERR_NONE);
    }
    GDALClose(out);
    GDALClose(in);
}

// Runs f, expects an exception of type E whose message contains every fragment.
template <class E, class F>
void expect_error(F&& f, const std::vector<std::string>& fragments) {
    try {
        f();
        ADD_FAILURE() << "no exception thrown";
    } catch (const E& e) {
        const std::string what = e.what();
        for (const auto& frag : fragments)
            EXPECT_NE(what.find(frag), std::string::npos)
                << "message '" << what << "' lacks '" << frag << "'";
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
    }
}

}  // namespace avalanche::gis::testing
