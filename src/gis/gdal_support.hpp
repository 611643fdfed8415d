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

// An in-memory raster (MEM driver) with the given size, type and band count.
DatasetPtr create_mem_raster(int width, int height, int bands, GDALDataType type);

// Lower-case copy, for extension and field-name comparisons.
std::string lower(std::string s);

}  // namespace avalanche::gis::detail
