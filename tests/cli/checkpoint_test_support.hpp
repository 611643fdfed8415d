#pragma once
// Helpers of the checkpoint tests: the binary started as a child process that the test
// can signal (fork/exec, not system()), and a product-by-product comparison of two
// output folders, read back with plain GDAL and HDF5 (not the writers under test).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cli_test_support.hpp"
#include "dem_test_support.hpp"
#include "io/io_test_support.hpp"
#include "support/same_bits.hpp"

namespace avalanche::test {

// The binary running in the background with stdout/stderr to files in `dir`.
class ChildRun {
  public:
    ChildRun(const ScratchDir& dir, const std::vector<std::string>& args, const std::string& tag)
        : err_(dir.file(tag + ".stderr")) {
        const std::string out = dir.file(tag + ".stdout");
        pid_ = ::fork();
        if (pid_ == 0) {
            const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int e = ::open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            ::dup2(o, 1);
            ::dup2(e, 2);
            std::vector<std::string> all{AVALANCHE_BINARY};
            all.insert(all.end(), args.begin(), args.end());
            std::vector<char*> argv;
            for (auto& a : all) argv.push_back(a.data());
            argv.push_back(nullptr);
            ::execv(AVALANCHE_BINARY, argv.data());
            ::_exit(127);
        }
    }
    ~ChildRun() {
        if (pid_ > 0 && !reaped_) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    ChildRun(const ChildRun&) = delete;
    ChildRun& operator=(const ChildRun&) = delete;

    // Waits up to `timeout` for `path` to exist while the child runs; false if the
    // child ended first or the time ran out.
    bool wait_for_file(const std::string& path, std::chrono::seconds timeout) {
        const auto end = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < end) {
            if (std::filesystem::exists(path)) return true;
            if (finished()) return std::filesystem::exists(path);
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return false;
    }
    bool finished() {
        if (reaped_) return true;
        int status = 0;
        if (::waitpid(pid_, &status, WNOHANG) == pid_) {
            reaped_ = true;
            status_ = status;
        }
        return reaped_;
    }
    void signal(int sig) { ::kill(pid_, sig); }
    // Waits for the end; returns the raw wait status.
    int wait() {
        if (!reaped_) {
            ::waitpid(pid_, &status_, 0);
            reaped_ = true;
        }
        return status_;
    }
    [[nodiscard]] std::string stderr_text() const { return read_text(err_); }

  private:
    pid_t pid_ = -1;
    bool reaped_ = false;
    int status_ = 0;
    std::string err_;
};

inline std::vector<std::string> files_with_extension(const std::string& dir,
                                                     const std::string& ext) {
    std::vector<std::string> out;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ext) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
}

inline std::string gdal_dataset_metadata(const std::string& path, const std::string& key) {
    GDALAllRegister();
    GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    if (ds == nullptr) return "<cannot open>";
    const char* v = ds->GetMetadataItem(key.c_str());
    std::string out = v ? v : "<missing>";
    GDALClose(ds);
    return out;
}

// A double attribute of a group of an HDF5 file, e.g. ("checkpoint.h5", "loop", "t").
inline double h5_group_attribute(const std::string& file, const std::string& group,
                                 const std::string& name) {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) return std::nan("");
    double v = std::nan("");
    const hid_t a = H5Aopen_by_name(f, group.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
    if (a >= 0) {
        H5Aread(a, H5T_NATIVE_DOUBLE, &v);
        H5Aclose(a);
    }
    H5Fclose(f);
    return v;
}

// summary.json without what differs between any two runs of the same scene.
inline nlohmann::json comparable_summary(const std::string& path) {
    nlohmann::json s = read_json_file(path);
    s.erase("wall_s");
    s.erase("command_line");
    s["performance"].erase("cell_updates_per_s");
    s["performance"].erase("phases_s");
    s["performance"].erase("openmp_wait");  // chosen by the machine's load at start
    return s;
}

// Every product of `b` equals that of `a`: raster pixels and nodata, CSV bytes, the
// results.h5 datasets and end attributes, summary.json apart from timing.
inline void expect_same_products(const std::string& a, const std::string& b) {
    const auto tifs = files_with_extension(a, ".tif");
    EXPECT_GE(tifs.size(), 7u);
    EXPECT_EQ(tifs, files_with_extension(b, ".tif"));
    for (const auto& name : tifs) {
        const Raster ra = read_raster(a + "/" + name), rb = read_raster(b + "/" + name);
        EXPECT_EQ(ra.width, rb.width) << name;
        EXPECT_EQ(ra.height, rb.height) << name;
        EXPECT_EQ(ra.nodata, rb.nodata) << name;
        EXPECT_TRUE(same_bits(ra.values, rb.values)) << name << " pixels differ";
    }
    for (const auto& name : files_with_extension(a, ".csv"))
        EXPECT_EQ(read_text(a + "/" + name), read_text(b + "/" + name)) << name;
    for (const char* set : {"time", "h", "u", "v"}) {
        const H5Array ha = read_h5_dataset(a + "/results.h5", set),
                      hb = read_h5_dataset(b + "/results.h5", set);
        EXPECT_EQ(ha.dims, hb.dims) << set;
        EXPECT_TRUE(same_bits(ha.values, hb.values)) << "results.h5 " << set << " differs";
    }
    for (const char* attr : {"simulated_time", "steps", "snapshots"})
        EXPECT_EQ(read_h5_double_attribute(a + "/results.h5", attr),
                  read_h5_double_attribute(b + "/results.h5", attr))
            << attr;
    const nlohmann::json sa = comparable_summary(a + "/summary.json"),
                         sb = comparable_summary(b + "/summary.json");
    EXPECT_EQ(sa, sb) << "summary.json differs:\n" << nlohmann::json::diff(sa, sb).dump(1);
}

}  // namespace avalanche::test
