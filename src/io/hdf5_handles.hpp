#pragma once
// Small RAII wrappers over the HDF5 C API, and attribute writers. Every failure becomes
// an OutputError naming the file, so HDF5's own error stack is never printed.
#include <hdf5.h>

#include <cstdint>
#include <span>
#include <string>

namespace avalanche::detail {

// Owns one hid_t and closes it with the matching H5?close.
class Hid {
  public:
    using Closer = herr_t (*)(hid_t);
    Hid() = default;
    Hid(hid_t id, Closer closer) : id_(id), closer_(closer) {}
    Hid(const Hid&) = delete;
    Hid& operator=(const Hid&) = delete;
    Hid(Hid&& o) noexcept : id_(o.id_), closer_(o.closer_) { o.id_ = H5I_INVALID_HID; }
    Hid& operator=(Hid&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = o.id_;
            closer_ = o.closer_;
            o.id_ = H5I_INVALID_HID;
        }
        return *this;
    }
    ~Hid() { reset(); }
    void reset() {
        if (id_ >= 0 && closer_) closer_(id_);
        id_ = H5I_INVALID_HID;
    }
    [[nodiscard]] hid_t get() const { return id_; }
    [[nodiscard]] bool valid() const { return id_ >= 0; }

  private:
    hid_t id_ = H5I_INVALID_HID;
    Closer closer_ = nullptr;
};

// Throws OutputError(file, "HDF5 could not <what>") when status < 0.
void h5_check(herr_t status, const std::string& file, const std::string& what);
// Same for a returned id; wraps it in a Hid with the closer.
Hid h5_take(hid_t id, Hid::Closer closer, const std::string& file, const std::string& what);

// Attributes on a file, group or dataset (loc). Strings are variable-length UTF-8.
void write_attribute(hid_t loc, const std::string& name, double value, const std::string& file);
void write_attribute(hid_t loc, const std::string& name, std::int64_t value,
                     const std::string& file);
void write_attribute(hid_t loc, const std::string& name, std::span<const double> values,
                     const std::string& file);
void write_attribute(hid_t loc, const std::string& name, const std::string& value,
                     const std::string& file);

}  // namespace avalanche::detail
