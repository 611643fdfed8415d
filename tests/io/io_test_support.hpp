#pragma once
// Helpers of the I/O tests: a scratch folder per test, and results.h5 read back with
// the HDF5 C API (independently of the writer's own code).
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/scratch_dir.hpp"

namespace avalanche::test {

struct H5Array {
    std::vector<hsize_t> dims;
    std::vector<double> values;
    [[nodiscard]] double at(hsize_t t, hsize_t row, hsize_t col) const {
        return values[(t * dims[1] + row) * dims[2] + col];
    }
};

inline H5Array read_h5_dataset(const std::string& file, const std::string& name) {
    H5Array out;
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0) throw std::runtime_error("cannot open " + file);
    const hid_t ds = H5Dopen2(f, name.c_str(), H5P_DEFAULT);
    const hid_t space = H5Dget_space(ds);
    const int rank = H5Sget_simple_extent_ndims(space);
    out.dims.resize(static_cast<std::size_t>(rank));
    H5Sget_simple_extent_dims(space, out.dims.data(), nullptr);
    hsize_t n = 1;
    for (hsize_t d : out.dims) n *= d;
    out.values.resize(n);
    if (n) H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data());
    H5Sclose(space);
    H5Dclose(ds);
    H5Fclose(f);
    return out;
}

inline std::vector<double> read_h5_double_attribute(const std::string& file,
                                                    const std::string& name) {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t a = H5Aopen(f, name.c_str(), H5P_DEFAULT);
    if (a < 0) {
        H5Fclose(f);
        throw std::runtime_error("no attribute " + name);
    }
    const hid_t space = H5Aget_space(a);
    const hssize_t n = H5Sget_simple_extent_npoints(space);
    std::vector<double> v(static_cast<std::size_t>(n));
    H5Aread(a, H5T_NATIVE_DOUBLE, v.data());
    H5Sclose(space);
    H5Aclose(a);
    H5Fclose(f);
    return v;
}

inline std::string read_h5_string_attribute(const std::string& file, const std::string& name) {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t a = H5Aopen(f, name.c_str(), H5P_DEFAULT);
    if (a < 0) {
        H5Fclose(f);
        throw std::runtime_error("no attribute " + name);
    }
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    char* text = nullptr;
    H5Aread(a, type, &text);
    std::string out = text ? text : "";
    H5free_memory(text);
    H5Tclose(type);
    H5Aclose(a);
    H5Fclose(f);
    return out;
}

// Replaces the root string attribute `name` of `file` (to stand for a file another
// program wrote).
inline void replace_h5_string_attribute(const std::string& file, const std::string& name,
                                        const std::string& value) {
    const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    if (f < 0) throw std::runtime_error("cannot open " + file);
    if (H5Aexists(f, name.c_str()) > 0) H5Adelete(f, name.c_str());
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t a = H5Acreate2(f, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = value.c_str();
    const herr_t written = a < 0 ? -1 : H5Awrite(a, type, &text);
    if (a >= 0) H5Aclose(a);
    H5Sclose(space);
    H5Tclose(type);
    H5Fclose(f);
    if (written < 0) throw std::runtime_error("cannot write the attribute " + name);
}

}  // namespace avalanche::test
