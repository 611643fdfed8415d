#include "hdf5_handles.hpp"

#include "avalanche/core/error.hpp"

namespace avalanche::detail {

namespace {
// HDF5 closes every file still open when the process exits. A file whose last flush
// failed (disk full, EFBIG under a file-size limit) cannot be closed, stays open, and
// that exit-time close then crashed inside HDF5 (SIGSEGV in H5F__close_cb, measured
// with HDF5 1.10 and RLIMIT_FSIZE) after the one-line error had been printed: exit 139
// instead of 4. Our files are closed by their owners (Hid); a leaked one is only ever
// a failed .part file. H5dont_atexit must run before the library initialises itself.
[[maybe_unused]] const herr_t kNoExitTimeClose = H5dont_atexit();
}  // namespace

void h5_check(herr_t status, const std::string& file, const std::string& what) {
    if (status < 0) throw OutputError(file, "HDF5 could not " + what);
}

Hid h5_take(hid_t id, Hid::Closer closer, const std::string& file, const std::string& what) {
    if (id < 0) throw OutputError(file, "HDF5 could not " + what);
    return Hid(id, closer);
}

namespace {
void write_raw(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type, hid_t space,
               const void* data, const std::string& file) {
    const std::string what = "write the attribute " + name;
    if (H5Aexists(loc, name.c_str()) > 0) h5_check(H5Adelete(loc, name.c_str()), file, what);
    Hid attr = h5_take(H5Acreate2(loc, name.c_str(), file_type, space, H5P_DEFAULT, H5P_DEFAULT),
                       H5Aclose, file, what);
    h5_check(H5Awrite(attr.get(), mem_type, data), file, what);
}
}  // namespace

void write_attribute(hid_t loc, const std::string& name, double value, const std::string& file) {
    Hid space = h5_take(H5Screate(H5S_SCALAR), H5Sclose, file, "create a dataspace");
    write_raw(loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), &value, file);
}

void write_attribute(hid_t loc, const std::string& name, std::int64_t value,
                     const std::string& file) {
    Hid space = h5_take(H5Screate(H5S_SCALAR), H5Sclose, file, "create a dataspace");
    write_raw(loc, name, H5T_STD_I64LE, H5T_NATIVE_INT64, space.get(), &value, file);
}

void write_attribute(hid_t loc, const std::string& name, std::span<const double> values,
                     const std::string& file) {
    const hsize_t n = values.size();
    Hid space = h5_take(H5Screate_simple(1, &n, nullptr), H5Sclose, file, "create a dataspace");
    write_raw(loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space.get(), values.data(), file);
}

void write_attribute(hid_t loc, const std::string& name, const std::string& value,
                     const std::string& file) {
    Hid type = h5_take(H5Tcopy(H5T_C_S1), H5Tclose, file, "create a string type");
    h5_check(H5Tset_size(type.get(), H5T_VARIABLE), file, "create a string type");
    h5_check(H5Tset_cset(type.get(), H5T_CSET_UTF8), file, "create a string type");
    Hid space = h5_take(H5Screate(H5S_SCALAR), H5Sclose, file, "create a dataspace");
    const char* ptr = value.c_str();
    write_raw(loc, name, type.get(), type.get(), space.get(), &ptr, file);
}

}  // namespace avalanche::detail
