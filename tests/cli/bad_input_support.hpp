#pragma once
// The binary inputs of the bad-input corpus (tests/data/bad/README.md), made at run time
// with GDAL from the bundled avaKot scene: small, exact, and no binary blobs in git. The
// text inputs (TOML, CSV, GeoJSON, ASCII grids, a VRT) are committed in tests/data/bad/.
#include <gdal_priv.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "dem_test_support.hpp"

namespace avalanche::test {

// The avaKot release polygon's bounding box (EPSG:31287), from ogrinfo: cells whose
// centre lies in it are the release cells on the 20 m grid.
struct Box {
    double x0, y0, x1, y1;
};
inline constexpr Box kAvaKotReleaseBox{177781.4, 376624.6, 177887.9, 376832.7};

// Copies `src` to `dst` (GeoTIFF) and sets the cells whose centre lies in `box` to
// `value`; declares `nodata` if asked, else keeps the source's declaration.
inline bool copy_with_cells_set(const std::string& src, const std::string& dst, const Box& box,
                                double value, bool declare_nodata, double nodata = 0.0) {
    if (!gdal_translate(src, dst, {"-of", "GTiff", "-ot", "Float32"})) return false;
    GDALDataset* ds = GDALDataset::Open(dst.c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE);
    if (ds == nullptr) return false;
    double gt[6];
    ds->GetGeoTransform(gt);
    const int w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
    std::vector<float> z(static_cast<std::size_t>(w) * h);
    GDALRasterBand* band = ds->GetRasterBand(1);
    bool ok = band->RasterIO(GF_Read, 0, 0, w, h, z.data(), w, h, GDT_Float32, 0, 0) == CE_None;
    for (int row = 0; row < h; ++row)
        for (int col = 0; col < w; ++col) {
            const double x = gt[0] + (col + 0.5) * gt[1], y = gt[3] + (row + 0.5) * gt[5];
            if (x >= box.x0 && x <= box.x1 && y >= box.y0 && y <= box.y1)
                z[static_cast<std::size_t>(row) * w + col] = static_cast<float>(value);
        }
    if (declare_nodata) ok = ok && band->SetNoDataValue(nodata) == CE_None;
    ok = ok && band->RasterIO(GF_Write, 0, 0, w, h, z.data(), w, h, GDT_Float32, 0, 0) == CE_None;
    GDALClose(ds);
    return ok;
}

// The first `bytes` bytes of `src`, as a file transferred halfway.
inline bool truncated_copy(const std::string& src, const std::string& dst, std::size_t bytes) {
    std::ifstream in(src, std::ios::binary);
    std::string data(bytes, '\0');
    in.read(data.data(), static_cast<std::streamsize>(bytes));
    if (static_cast<std::size_t>(in.gcount()) != bytes) return false;
    std::ofstream(dst, std::ios::binary) << data;
    return true;
}

// run_binary with environment assignments ("NAME=value ...") in front of the command.
inline ProcessResult run_binary_with_env(const ScratchDir& dir, const std::string& env,
                                         const std::string& args) {
    const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
    const std::string cmd = env + (env.empty() ? "" : " ") + "'" + AVALANCHE_BINARY + "' " + args +
                            " >'" + out + "' 2>'" + err + "'";
    const int status = std::system(cmd.c_str());
    ProcessResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
}

// Every input of the corpus that is not a committed text file, in one folder.
struct GeneratedInputs {
    std::string dem;                  // avaKot at 20 m: the good DEM every DEM case starts from
    std::string truncated_dem;        // its GeoTIFF cut after the header and a few rows
    std::string dem_nan_release;      // NaN elevations under the release
    std::string dem_void_release;     // declared nodata (-9999) under the release
    std::string dem_all_nan;          // every elevation NaN
    std::string shp_without_shx;      // the release as a Shapefile without its .shx
    std::string shp_without_dbf;      // ... without its .dbf
    std::string thickness_wrong_crs;  // a thickness raster labelled EPSG:32632 (UTM 32N)
                                      // but holding Austria Lambert coordinates
    std::string thickness_negative;   // a thickness raster with -1 m cells
    std::string good_chute;           // a valid chute scenario
    std::string a_file;               // a regular file, where a folder is expected
    std::string old_results;          // a folder holding an earlier run's summary.json
    std::string read_only;            // a 0555 folder, or below a file when run as root
    bool ok = false;
};

inline GeneratedInputs make_generated_inputs(const ScratchDir& dir) {
    GeneratedInputs g;
    const std::string release = avaKot("avaKot_release.gpkg");
    g.dem = dir.file("dem20.tif");
    bool ok = gdal_warp(avaKot("avaKot_dem.tif"), g.dem, {"-tr", "20", "20", "-r", "average"});

    // A striped GeoTIFF cut after its header and first rows: GDAL opens it, the rows
    // beyond the cut cannot be read.
    const std::string striped = dir.file("striped.tif");
    ok = ok && gdal_translate(g.dem, striped, {"-co", "TILED=NO", "-co", "BLOCKYSIZE=1"});
    g.truncated_dem = dir.file("truncated.tif");
    ok = ok && truncated_copy(striped, g.truncated_dem, std::filesystem::file_size(striped) / 3);

    const double nan = std::numeric_limits<double>::quiet_NaN();
    g.dem_nan_release = dir.file("dem_nan_under_release.tif");
    ok = ok && copy_with_cells_set(g.dem, g.dem_nan_release, kAvaKotReleaseBox, nan, false);
    g.dem_void_release = dir.file("dem_void_under_release.tif");
    ok = ok &&
         copy_with_cells_set(g.dem, g.dem_void_release, kAvaKotReleaseBox, -9999.0, true, -9999.0);
    g.dem_all_nan = dir.file("dem_all_nan.tif");
    ok = ok && copy_with_cells_set(g.dem, g.dem_all_nan, {-1e9, -1e9, 1e9, 1e9}, nan, false);

    for (const char* missing : {"shx", "dbf"}) {
        const std::string folder = dir.file(std::string("no_") + missing);
        std::filesystem::create_directories(folder);
        const std::string shp = folder + "/release.shp";
        ok = ok && ogr2ogr(shp, release, {"-f", "ESRI Shapefile"}) &&
             std::filesystem::remove(folder + "/release." + missing);
        (std::string(missing) == "shx" ? g.shp_without_shx : g.shp_without_dbf) = shp;
    }

    // A 1 m thickness over the release box, first in the DEM's CRS, then relabelled.
    const std::string thick = dir.file("thickness.tif");
    ok = ok && gdal_translate(g.dem, thick, {"-ot", "Float32", "-scale", "0", "1e9", "1", "1"});
    g.thickness_wrong_crs = dir.file("thickness_epsg32632.tif");
    ok = ok && gdal_translate(thick, g.thickness_wrong_crs, {"-a_srs", "EPSG:32632"});
    g.thickness_negative = dir.file("thickness_negative.tif");
    ok = ok &&
         gdal_translate(thick, dir.file("thickness_zero.tif"), {"-scale", "0", "1e9", "0", "0"}) &&
         copy_with_cells_set(dir.file("thickness_zero.tif"), g.thickness_negative,
                             kAvaKotReleaseBox, -1.0, false);

    g.good_chute = dir.write("chute.toml", kSmallChute);
    g.a_file = dir.write("a-file", "not a folder\n");
    g.old_results = dir.file("old-results");
    std::filesystem::create_directories(g.old_results);
    dir.write("old-results/summary.json", "{\"from\": \"an earlier run\"}\n");
    // chmod does not stop root: then a path below a regular file, which nobody can create.
    if (::geteuid() == 0) {
        g.read_only = g.a_file + "/out";
    } else {
        g.read_only = dir.file("read-only");
        std::filesystem::create_directories(g.read_only);
        ::chmod(g.read_only.c_str(), 0555);
    }
    g.ok = ok;
    return g;
}

}  // namespace avalanche::test

namespace avalanche::test {

// Runs the binary in a forked child whose files may not grow beyond `max_file_bytes`
// (RLIMIT_FSIZE) and which ignores SIGXFSZ, so that a write past the limit fails with
// EFBIG as on a full disk instead of killing the process.
inline ProcessResult run_binary_with_file_limit(const ScratchDir& dir,
                                                const std::vector<std::string>& args,
                                                rlim_t max_file_bytes) {
    const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::signal(SIGXFSZ, SIG_IGN);  // inherited through exec
        const rlimit limit{max_file_bytes, max_file_bytes};
        ::setrlimit(RLIMIT_FSIZE, &limit);
        std::FILE* o = std::freopen(out.c_str(), "w", stdout);
        std::FILE* e = std::freopen(err.c_str(), "w", stderr);
        if (o == nullptr || e == nullptr) ::_exit(126);
        std::vector<char*> argv{const_cast<char*>(AVALANCHE_BINARY)};
        for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        ::execv(AVALANCHE_BINARY, argv.data());
        ::_exit(127);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    ProcessResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read_text(out);
    r.err = read_text(err);
    return r;
}

}  // namespace avalanche::test
