#pragma once
// A scalar cell field on a Grid, padded with ghost layers on every side so that
// stencils near the edges need no branches. Storage is one contiguous
// vector, row-major (x fastest), so row sweeps vectorise; a field written whole sits on
// huge pages (field_storage.hpp). Each row starts and its column 0 sits on a 64-byte
// cache line (column0(), stride(): the ghost columns just before it, the row padded to
// whole lines), so that a row kernel's vector loads from column 0 on do not straddle
// two lines (docs/performance.md, "Rows on cache lines"). The padding holds no cell:
// fill() and copies write it, nothing reads it. packed() gives the cells without it,
// the layout of checkpoint files.
//
// A field the same in every row, ghost rows included (same_in_every_row: the chute's
// terrain, which varies only down the slope), stores that one row: every row reads it,
// through the const accessors and row(j) alike. Its row step is 0, so raw() is one row
// long and a flat offset taken from another field's index() does not address it: read
// it by (i, j) or row(j). A non-const accessor (operator(), row, raw, set_interior)
// first gives it storage for every row, the values kept, so a writer that makes the
// rows differ cannot write one row for all of them.
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
        : nx_(nx),
          ny_(ny),
          ng_(ghosts),
          column0_(column0_of(ghosts)),
          stride_(stride_of(nx, ghosts)),
          row_step_(stride_),
          data_(cells_with_ghosts(nx, ny, ghosts)) {
        if (!is_positive_zero(value)) fill(value);
    }
    // A field whose rows are all alike (see above): one row of storage, filled with value.
    // Write it through every_row().
    static Field2D same_in_every_row(int nx, int ny, int ghosts, double value = 0.0) {
        Field2D f;
        f.nx_ = nx;
        f.ny_ = ny;
        f.ng_ = ghosts;
        f.column0_ = column0_of(ghosts);
        f.stride_ = stride_of(nx, ghosts);
        f.row_step_ = 0;
        f.data_ = FieldStorage(static_cast<std::size_t>(f.stride_));
        if (!is_positive_zero(value)) std::fill(f.data_.begin(), f.data_.end(), value);
        return f;
    }

    // A copy writes every cell: on huge pages (field_storage.hpp), where std::vector's copy
    // would leave it in small ones. Assignment to a field of the same size reuses its
    // memory; to one of another size it is a copy, moved in.
    Field2D(const Field2D& other)
        : nx_(other.nx_),
          ny_(other.ny_),
          ng_(other.ng_),
          column0_(other.column0_),
          stride_(other.stride_),
          row_step_(other.row_step_),
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
        column0_ = other.column0_;
        stride_ = other.stride_;
        row_step_ = other.row_step_;
        return *this;
    }
    Field2D(Field2D&&) noexcept = default;
    Field2D& operator=(Field2D&&) noexcept = default;
    ~Field2D() = default;

    [[nodiscard]] int nx() const { return nx_; }
    [[nodiscard]] int ny() const { return ny_; }
    [[nodiscard]] int ghosts() const { return ng_; }
    [[nodiscard]] int stride() const { return stride_; }
    // Position of column 0 in a row of the storage (the ghost columns before it).
    [[nodiscard]] int column0() const { return column0_; }
    // Rows start on a cache line (kRowAlignment values) and column 0 does too, so that
    // the row kernels' vector loads of a row do not straddle two lines.
    static constexpr int kRowAlignment = 8;
    static constexpr int column0_of(int ghosts) { return round_up(ghosts); }
    static constexpr int stride_of(int nx, int ghosts) {
        return round_up(column0_of(ghosts) + nx + ghosts);
    }
    static constexpr int round_up(int n) {
        return (n + kRowAlignment - 1) / kRowAlignment * kRowAlignment;
    }
    [[nodiscard]] bool empty() const { return data_.empty(); }
    // True while the field stores one row that every row reads (same_in_every_row).
    [[nodiscard]] bool same_in_every_row() const { return row_step_ != stride_; }

    // Linear index of cell (i, j) in raw(); i in [-ng, nx+ng), j in [-ng, ny+ng).
    [[nodiscard]] std::ptrdiff_t index(int i, int j) const {
        assert(i >= -ng_ && i < nx_ + ng_ && j >= -ng_ && j < ny_ + ng_);
        return static_cast<std::ptrdiff_t>(j + ng_) * row_step_ + (column0_ + i);
    }
    double& operator()(int i, int j) {
        store_every_row();
        return data_[index(i, j)];
    }
    double operator()(int i, int j) const { return data_[index(i, j)]; }
    double* row(int j) {
        store_every_row();
        return data_.data() + index(0, j);
    }
    [[nodiscard]] const double* row(int j) const { return data_.data() + index(0, j); }
    // Column 0 of the one row a field same_in_every_row stores, to write it.
    double* every_row() {
        assert(same_in_every_row());
        return data_.data() + column0_;
    }

    // Fills every cell; a field same_in_every_row stays one row.
    void fill(double v) {
        advise_written_whole();
        std::fill(data_.begin(), data_.end(), v);
    }
    // Before every cell is written (a copy of the elevation, say): the field is offered
    // for huge pages (field_storage.hpp says why only then).
    void advise_written_whole() { avalanche::advise_written_whole(data_.data(), data_.size() * sizeof(double)); }
    FieldStorage& raw() {
        store_every_row();
        return data_;
    }
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
    // The cells of an array in this field's layout (its raw() or a CellVector of as many
    // values), ghosts included, row by row without the rows' padding: (nx + 2 ng) x
    // (ny + 2 ng) values, the layout of checkpoint files, whatever the padding.
    [[nodiscard]] std::size_t packed_size() const {
        return static_cast<std::size_t>(nx_ + 2 * ng_) * static_cast<std::size_t>(ny_ + 2 * ng_);
    }
    template <class Out, class In>
    [[nodiscard]] std::vector<Out> packed(const In* values) const {
        std::vector<Out> out;
        out.reserve(packed_size());
        for (int j = -ng_; j < ny_ + ng_; ++j)
            for (int i = -ng_; i < nx_ + ng_; ++i)
                out.push_back(static_cast<Out>(values[index(i, j)]));
        return out;
    }
    [[nodiscard]] std::vector<double> packed() const { return packed<double>(data_.data()); }
    // The inverse: packed values (packed_size() of them) into an array in this layout.
    template <class Out, class In>
    void unpack(const In* values, Out* out) const {
        for (int j = -ng_; j < ny_ + ng_; ++j)
            for (int i = -ng_; i < nx_ + ng_; ++i) out[index(i, j)] = static_cast<Out>(*values++);
    }
    void set_packed(const std::vector<double>& values) {
        assert(values.size() == packed_size());
        unpack(values.data(), raw().data());
    }

    // Copies the nearest interior value into every ghost cell (zero gradient). A field
    // same_in_every_row has its ghost rows already: only its row's ends are written.
    void extend_to_ghosts() {
        const bool one_row = same_in_every_row();
        for (int j = 0; j < (one_row ? 1 : ny_); ++j) {
            for (int g = 1; g <= ng_; ++g) {
                at(-g, j) = at(0, j);
                at(nx_ - 1 + g, j) = at(nx_ - 1, j);
            }
        }
        if (one_row) return;
        for (int g = 1; g <= ng_; ++g) {
            for (int i = -ng_; i < nx_ + ng_; ++i) {
                at(i, -g) = at(i, 0);
                at(i, ny_ - 1 + g) = at(i, ny_ - 1);
            }
        }
    }

private:
    double& at(int i, int j) { return data_[index(i, j)]; }
    // Before a write that may make the rows differ: a field same_in_every_row gets storage
    // for every row, each a copy of the one it had.
    void store_every_row() {
        if (row_step_ == stride_) [[likely]]
            return;
        FieldStorage all(cells_with_ghosts(nx_, ny_, ng_));
        for (int j = 0; j < ny_ + 2 * ng_; ++j)
            std::copy(data_.begin(), data_.end(), all.begin() + static_cast<std::ptrdiff_t>(j) * stride_);
        data_ = std::move(all);
        row_step_ = stride_;
    }

    static std::size_t cells_with_ghosts(int nx, int ny, int ghosts) {
        return static_cast<std::size_t>(stride_of(nx, ghosts)) *
               static_cast<std::size_t>(ny + 2 * ghosts);
    }
    static bool is_positive_zero(double v) { return v == 0.0 && !std::signbit(v); }

    int nx_ = 0, ny_ = 0, ng_ = 0, column0_ = 0, stride_ = 0;
    int row_step_ = 0;  // stride_, or 0 where every row reads one (same_in_every_row)
    FieldStorage data_;
};

}  // namespace avalanche
