#pragma once
// The part of the grid the solver works on: the bounding box of the cells that
// hold material, widened by a margin so that everything that can become wet
// within one time step is inside (each advection update moves mass by at most
// one cell, and a step holds at most two of them; the WAF stencil adds two).
#include <algorithm>
#include <cstddef>
#include <span>

namespace avalanche {

struct ActiveBox {
    int i0 = 0, i1 = 0;  // cells i0 <= i < i1
    int j0 = 0, j1 = 0;  // cells j0 <= j < j1

    [[nodiscard]] bool operator==(const ActiveBox&) const = default;
    [[nodiscard]] bool empty() const { return i1 <= i0 || j1 <= j0; }
    [[nodiscard]] std::size_t cells() const {
        return empty() ? 0 : static_cast<std::size_t>(i1 - i0) * static_cast<std::size_t>(j1 - j0);
    }
    [[nodiscard]] ActiveBox widened(int m, int nx, int ny) const {
        if (empty()) return *this;
        return {std::max(0, i0 - m), std::min(nx, i1 + m), std::max(0, j0 - m), std::min(ny, j1 + m)};
    }
    // The cells of the box on a grid of nx x ny cells (an empty box where none are).
    [[nodiscard]] ActiveBox clipped(int nx, int ny) const {
        const ActiveBox c{std::max(i0, 0), std::min(i1, nx), std::max(j0, 0), std::min(j1, ny)};
        return c.empty() ? ActiveBox{} : c;
    }
    // The smallest box holding both (an empty box holds nothing).
    [[nodiscard]] ActiveBox united(const ActiveBox& o) const {
        if (o.empty()) return *this;
        if (empty()) return o;
        return {std::min(i0, o.i0), std::max(i1, o.i1), std::min(j0, o.j0), std::max(j1, o.j1)};
    }
};

// f(i, j, k) for every cell of box b, row by row, with k = j * nx + i the cell's index in
// a dense grid of nx columns (the hazard maps' layout).
template <class F>
void for_each_cell(const ActiveBox& b, int nx, F&& f) {
    for (int j = b.j0; j < b.j1; ++j)
        for (int i = b.i0; i < b.i1; ++i)
            f(i, j, static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + i);
}

// Where thread t of n starts in a list of strips: `before[k]` is the work (cells) of
// the strips before strip k, before.back() the whole; the strip boundary nearest to
// t / n of the work (n for t >= n). Nearest, not the first at or beyond: that one gave
// the first thread half a strip too many on average.
[[nodiscard]] inline int share_start(std::span<const std::size_t> before, int t, int n) {
    const int strips = static_cast<int>(before.size()) - 1;
    if (t >= n) return strips;
    const std::size_t target = before.back() * static_cast<std::size_t>(t) / static_cast<std::size_t>(n);
    auto k = std::lower_bound(before.begin(), before.end() - 1, target);
    if (k != before.begin() && target - *(k - 1) < *k - target) --k;
    return static_cast<int>(k - before.begin());
}

}  // namespace avalanche
