#pragma once
// The part of the grid the solver works on: the bounding box of the cells that
// hold material, widened by a margin so that everything that can become wet
// within one time step is inside (each advection update moves mass by at most
// one cell, and a step holds at most two of them; the WAF stencil adds two).
#include <algorithm>
#include <cstddef>

namespace avalanche {

struct ActiveBox {
    int i0 = 0, i1 = 0;  // cells i0 <= i < i1
    int j0 = 0, j1 = 0;  // cells j0 <= j < j1

    [[nodiscard]] bool empty() const { return i1 <= i0 || j1 <= j0; }
    [[nodiscard]] std::size_t cells() const {
        return empty() ? 0 : static_cast<std::size_t>(i1 - i0) * static_cast<std::size_t>(j1 - j0);
    }
    [[nodiscard]] ActiveBox widened(int m, int nx, int ny) const {
        if (empty()) return *this;
        return {std::max(0, i0 - m), std::min(nx, i1 + m), std::max(0, j0 - m), std::min(ny, j1 + m)};
    }
};

}  // namespace avalanche
