#pragma once
// A scalar cell field on a Grid, padded with ghost layers on every side so that
// stencils near the edges need no branches. Storage is one contiguous
// vector, row-major (x fastest), so row sweeps vectorise; a field written whole sits on
// huge pages (field_storage.hpp).
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <vector>

#include "avalanche/core/field_storage.hpp"

namespace avalanche {

class Field2D {
public:
    Field2D() = default;
    // A field of zeros is not written: the storage comes zeroed (field_storage.hpp), so
    // the memory of cells nobody writes is never touched. Any other value is written
    // everywhere, on huge pages.
    Field2D(int nx, int ny, int ghosts, double value = 0.0)
        : nx_(nx), ny_(ny), ng_(ghosts), stride_(nx + 2 * ghosts),
          data_(cells_with_ghosts(nx, ny, ghosts)) {
        if (!is_positive_zero(value)) fill(value);
    }

    // A copy writes every cell: on huge pages (field_storage.hpp), where std::vector's copy
    // would leave it in small ones. Assignment to a field of the same size reuses its
    // memory; to one of another size it is a copy, moved in.
    Field2D(const Field2D& other)
        : nx_(other.nx_), ny_(other.ny_), ng_(other.ng_), stride_(other.stride_),
          data_(other.data_.size()) {
        advise_written_whole();
        std::copy(other.data_.begin(), other.data_.end(), data_.begin());
    }
    Field2D& operator=(const Field2D& other) {
        if (this == &other) return *this;
        if (data_.size() != other.data_.size()) return *this = Field2D(other);
        std::copy(other.data_.begin(), other.data_.end(), data_.begin());
        nx_ = other.nx_;
        ny_ = other.ny_;
        ng_ = other.ng_;
        stride_ = other.stride_;
        return *this;
    }
    Field2D(Field2D&&) noexcept = default;
    Field2D& operator=(Field2D&&) noexcept = default;
    ~Field2D() = default;

    [[nodiscard]] int nx() const { return nx_; }
    [[nodiscard]] int ny() const { return ny_; }
    [[nodiscard]] int ghosts() const { return ng_; }
    [[nodiscard]] int stride() const { return stride_; }
    [[nodiscard]] bool empty() const { return data_.empty(); }

    // Linear index of cell (i, j); i in [-ng, nx+ng), j in [-ng, ny+ng).
    [[nodiscard]] std::ptrdiff_t index(int i, int j) const {
        assert(i >= -ng_ && i < nx_ + ng_ && j >= -ng_ && j < ny_ + ng_);
        return static_cast<std::ptrdiff_t>(j + ng_) * stride_ + (i + ng_);
    }
    double& operator()(int i, int j) { return data_[index(i, j)]; }
    double operator()(int i, int j) const { return data_[index(i, j)]; }
    double* row(int j) { return data_.data() + index(0, j); }
    [[nodiscard]] const double* row(int j) const { return data_.data() + index(0, j); }

    void fill(double v) {
        advise_written_whole();
        std::fill(data_.begin(), data_.end(), v);
    }
    // Before every cell is written (a copy of the elevation, say): the field is offered
    // for huge pages (field_storage.hpp says why only then).
    void advise_written_whole() { avalanche::advise_written_whole(data_.data(), data_.size() * sizeof(double)); }
    FieldStorage& raw() { return data_; }
    [[nodiscard]] const FieldStorage& raw() const { return data_; }

    // Interior values as a dense nx*ny row-major vector (j = 0 first).
    [[nodiscard]] std::vector<double> interior() const {
        std::vector<double> out(static_cast<std::size_t>(nx_) * ny_);
        for (int j = 0; j < ny_; ++j)
            std::copy(row(j), row(j) + nx_, out.begin() + static_cast<std::ptrdiff_t>(j) * nx_);
        return out;
    }
    void set_interior(const std::vector<double>& values) {
        assert(values.size() == static_cast<std::size_t>(nx_) * ny_);
        for (int j = 0; j < ny_; ++j)
            std::copy(values.begin() + static_cast<std::ptrdiff_t>(j) * nx_,
                      values.begin() + static_cast<std::ptrdiff_t>(j + 1) * nx_, row(j));
    }
    // Copies the nearest interior value into every ghost cell (zero gradient).
    void extend_to_ghosts() {
        for (int j = 0; j < ny_; ++j) {
            for (int g = 1; g <= ng_; ++g) {
                (*this)(-g, j) = (*this)(0, j);
                (*this)(nx_ - 1 + g, j) = (*this)(nx_ - 1, j);
            }
        }
        for (int g = 1; g <= ng_; ++g) {
            for (int i = -ng_; i < nx_ + ng_; ++i) {
                (*this)(i, -g) = (*this)(i, 0);
                (*this)(i, ny_ - 1 + g) = (*this)(i, ny_ - 1);
            }
        }
    }

private:
    static std::size_t cells_with_ghosts(int nx, int ny, int ghosts) {
        return static_cast<std::size_t>(nx + 2 * ghosts) * static_cast<std::size_t>(ny + 2 * ghosts);
    }
    static bool is_positive_zero(double v) { return v == 0.0 && !std::signbit(v); }

    int nx_ = 0, ny_ = 0, ng_ = 0, stride_ = 0;
    FieldStorage data_;
};

}  // namespace avalanche
