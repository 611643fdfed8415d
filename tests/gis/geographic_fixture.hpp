#pragma once
// An ASTER-GDEM-like fixture made from the bundled avaKot DEM: EPSG:4326, 1 arc-second,
// Int16 with nodata -9999 (data/README.md recipe), and the same split into two tiles.
#include <gdal_utils.h>

#include <string>
#include <vector>

#include "gis_test_support.hpp"

namespace avalanche::gis::testing {

inline void run_gdalwarp(const std::string& src, const std::string& dst,
                         const std::vector<std::string>& args) {
    GDALAllRegister();
    CPLStringList list;
    for (const auto& a : args) list.AddString(a.c_str());
    GDALWarpAppOptions* opts = GDALWarpAppOptionsNew(list.List(), nullptr);
    GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
    ASSERT_NE(in, nullptr);
    GDALDatasetH out = GDALWarp(dst.c_str(), nullptr, 1, &in, opts, nullptr);
    ASSERT_NE(out, nullptr);
    GDALClose(out);
    GDALClose(in);
    GDALWarpAppOptionsFree(opts);
}

inline void run_gdal_translate(const std::string& src, const std::string& dst,
                               const std::vector<std::string>& args) {
    GDALAllRegister();
    CPLStringList list;
    for (const auto& a : args) list.AddString(a.c_str());
    GDALTranslateOptions* opts = GDALTranslateOptionsNew(list.List(), nullptr);
    GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
    ASSERT_NE(in, nullptr);
    GDALDatasetH out = GDALTranslate(dst.c_str(), in, opts, nullptr);
    ASSERT_NE(out, nullptr);
    GDALClose(out);
    GDALClose(in);
    GDALTranslateOptionsFree(opts);
}

// Writes geo.tif (whole) and west.tif / east.tif (two tiles) into `tmp`.
inline void make_geographic_dem(const TempDir& tmp) {
    run_gdalwarp(avaKot("avaKot_dem.tif"), tmp.file("geo.tif"),
                 {"-t_srs", "EPSG:4326", "-tr", "0.000277777777778", "0.000277777777778", "-ot",
                  "Int16", "-dstnodata", "-9999", "-r", "bilinear"});
    int w = 0, h = 0;
    read_raw_rows(tmp.file("geo.tif"), &w, &h);
    const int half = w / 2;
    run_gdal_translate(tmp.file("geo.tif"), tmp.file("west.tif"),
                       {"-srcwin", "0", "0", std::to_string(half), std::to_string(h)});
    run_gdal_translate(
        tmp.file("geo.tif"), tmp.file("east.tif"),
        {"-srcwin", std::to_string(half), "0", std::to_string(w - half), std::to_string(h)});
}

}  // namespace avalanche::gis::testing
