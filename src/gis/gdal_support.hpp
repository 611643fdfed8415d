#pragma once
// Private plumbing shared by the GIS sources: GDAL registration, the CPLError
// scope that turns GDAL failures into project errors (STYLE.md convention 7),
// owning dataset pointers and the openers that name the file in every error.
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <memory>
#include <string>
#include <vector>

namespace avalanche::gis::detail {

// GDALAllRegister once per process (thread-safe).
void ensure_gdal_registered();

// While alive, every CPLError on this thread is recorded here instead of being
// printed to stderr. API functions open one scope and turn recorded failures
// into InputError / OutputError with the file name, so the user sees one line.
class GdalErrorScope {
  public:
    GdalErrorScope();
    ~GdalErrorScope();
    GdalErrorScope(const GdalErrorScope&) = delete;
    GdalErrorScope& operator=(const GdalErrorScope&) = delete;

    [[nodiscard]] bool failed() const { return !failures_.empty(); }
    // " (GDAL: <first failure>)" or "" -- to append to an error message.
    [[nodiscard]] std::string reason() const;
    [[nodiscard]] const std::vector<std::string>& warnings() const { return warnings_; }
    void clear();

  private:
    static void CPL_STDCALL handler(CPLErr level, CPLErrorNum number, const char* message);
    std::vector<std::string> failures_;
    std::vector<std::string> warnings_;
};

struct DatasetCloser {
    void operator()(GDALDataset* ds) const { GDALClose(GDALDataset::ToHandle(ds)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

// Open a raster / vector dataset read-only; InputError naming the file otherwise.
DatasetPtr open_raster(const std::string& path, const GdalErrorScope& errors);
DatasetPtr open_vector(const std::string& path, const GdalErrorScope& errors);

// The dataset's layers that have a geometry column. Attribute-only tables hold nothing to
// read: QGIS, for one, keeps the styles saved in a GeoPackage in such a table
// ('layer_styles').
std::vector<OGRLayer*> geometry_layers(GDALDataset& ds);

// A copy of the geometry with its curves (CurvePolygon, MultiSurface, CircularString
// rings) approximated by line segments, as GDALRasterizeGeometries burns only linear
// geometries; a linear geometry is copied unchanged.
std::unique_ptr<OGRGeometry> linear_copy(const OGRGeometry& g);

// An in-memory raster (MEM driver) with the given size, type and band count.
DatasetPtr create_mem_raster(int width, int height, int bands, GDALDataType type);

// Lower-case copy, for extension and field-name comparisons.
std::string lower(std::string s);

}  // namespace avalanche::gis::detail
