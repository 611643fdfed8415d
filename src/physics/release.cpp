#include "avalanche/physics/release.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "avalanche/core/error.hpp"

namespace avalanche {

namespace {
struct ThicknessAt {
    double x, y;
    double operator()(const CapRelease& c) const {
        const double r2 = (x - c.center[0]) * (x - c.center[0]) + (y - c.center[1]) * (y - c.center[1]);
        return r2 < c.radius * c.radius ? std::sqrt(c.radius * c.radius - r2) : 0.0;
    }
    double operator()(const ParaboloidRelease& p) const {
        const double r2 = (x - p.center[0]) * (x - p.center[0]) + (y - p.center[1]) * (y - p.center[1]);
        return r2 < p.radius * p.radius ? p.thickness * (1.0 - r2 / (p.radius * p.radius)) : 0.0;
    }
    double operator()(const BoxRelease& b) const {
        return (x >= b.x[0] && x <= b.x[1] && y >= b.y[0] && y <= b.y[1]) ? b.thickness : 0.0;
    }
};

// The shape's extent {x_min, x_max, y_min, y_max}: the thickness is zero outside it.
struct Extent {
    double x0, x1, y0, y1;
};
struct ExtentOf {
    Extent operator()(const CapRelease& c) const {
        return {c.center[0] - c.radius, c.center[0] + c.radius, c.center[1] - c.radius,
                c.center[1] + c.radius};
    }
    Extent operator()(const ParaboloidRelease& p) const {
        return {p.center[0] - p.radius, p.center[0] + p.radius, p.center[1] - p.radius,
                p.center[1] + p.radius};
    }
    Extent operator()(const BoxRelease& b) const { return {b.x[0], b.x[1], b.y[0], b.y[1]}; }
};

// The half-open range of cell indices [first, last) of n cells of size d from origin o
// that can hold a sub-sample inside [lo, hi]; one cell of margin on either side, so
// that rounding in the index cannot drop a cell the shape touches.
std::pair<int, int> cells_over(double lo, double hi, double o, double d, int n) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {0, n};  // sample every cell
    const double first = std::floor((lo - o) / d) - 1.0;
    const double last = std::floor((hi - o) / d) + 2.0;
    const auto clamp = [n](double k) { return static_cast<int>(std::clamp(k, 0.0, double(n))); };
    return {clamp(first), clamp(last)};
}

void require_positive(double v, const char* key) {
    if (!std::isfinite(v) || v <= 0.0) throw ConfigError(key, "expected a positive value in metres");
}
}  // namespace

void validate(const ReleaseShape& r) {
    std::visit(
        [](const auto& s) {
            using T = std::decay_t<decltype(s)>;
            if constexpr (std::is_same_v<T, CapRelease>) {
                require_positive(s.radius, "release.radius");
            } else if constexpr (std::is_same_v<T, ParaboloidRelease>) {
                require_positive(s.radius, "release.radius");
                require_positive(s.thickness, "release.thickness");
            } else {
                require_positive(s.thickness, "release.thickness");
                if (!(s.x[1] > s.x[0])) throw ConfigError("release.x", "expected [x1, x2] with x1 < x2");
                if (!(s.y[1] > s.y[0])) throw ConfigError("release.y", "expected [y1, y2] with y1 < y2");
            }
        },
        r);
}

double release_thickness_at(const ReleaseShape& r, double x, double y) {
    return std::visit(ThicknessAt{x, y}, r);
}

ActiveBox release_cells(const ReleaseShape& r, const Grid& grid) {
    const Extent e = std::visit(ExtentOf{}, r);
    const auto [i0, i1] = cells_over(e.x0, e.x1, grid.x0, grid.dx, grid.nx);
    const auto [j0, j1] = cells_over(e.y0, e.y1, grid.y0, grid.dy, grid.ny);
    return i1 > i0 && j1 > j0 ? ActiveBox{i0, i1, j0, j1} : ActiveBox{};
}

Field2D rasterize_release(const ReleaseShape& r, const Grid& grid, int subsamples) {
    // Zeros left unwritten (field_storage.hpp): only the shape's cells are written.
    Field2D out(grid.nx, grid.ny, kGhostLayers);
    const double inv = 1.0 / (subsamples * subsamples);
    // Sub-sample rows are summed in mirror pairs (b, n-1-b), so that a release
    // symmetric about a cell edge rasterizes to bitwise-symmetric cells: the
    // solver's mirror symmetry is then testable to round-off.
    const auto row_sum = [&](int i, int j, int b) {
        const double y = grid.y0 + (j + (b + 0.5) / subsamples) * grid.dy;
        double sum = 0.0;
        for (int a = 0; a < subsamples; ++a)
            sum += release_thickness_at(r, grid.x0 + (i + (a + 0.5) / subsamples) * grid.dx, y);
        return sum;
    };
    // Only the cells over the shape's extent are sampled (8 x 8 samples a cell: on a
    // 2000 x 2000 grid the whole grid took half a second for a release of 10 x 10 cells);
    // every sample outside the extent is zero, so the field is the same to the bit.
    const ActiveBox cells = release_cells(r, grid);
    for (int j = cells.j0; j < cells.j1; ++j) {
        for (int i = cells.i0; i < cells.i1; ++i) {
            double sum = 0.0;
            for (int b = 0; b < subsamples / 2; ++b) sum += row_sum(i, j, b) + row_sum(i, j, subsamples - 1 - b);
            if (subsamples % 2) sum += row_sum(i, j, subsamples / 2);
            out(i, j) = sum * inv;
        }
    }
    return out;
}

// Only the released cells are written (and their terrain made, terrain.hpp): the state
// starts as zeros that are not written, so a small release on a large DEM leaves the
// rest of the grid's memory untouched. Elsewhere h stays 0, as 0 / normal_thickness was.
State state_at_rest(const Grid& grid, const Field2D& thickness, const TerrainFields& terrain,
                    ActiveBox* released) {
    return state_at_rest(grid, thickness, terrain, ActiveBox{0, grid.nx, 0, grid.ny}, released);
}

State state_at_rest(const Grid& grid, const Field2D& thickness, const TerrainFields& terrain,
                    const ActiveBox& within, ActiveBox* released) {
    State s(grid);
    int i0 = grid.nx, i1 = 0, j0 = grid.ny, j1 = 0;
    const ActiveBox search = within.clipped(grid.nx, grid.ny);
    for (int j = search.j0; j < search.j1; ++j) {
        const double* row = thickness.row(j);
        for (int i = search.i0; i < search.i1; ++i)
            if (row[i] != 0.0) {
                i0 = std::min(i0, i);
                i1 = std::max(i1, i + 1);
                j0 = std::min(j0, j);
                j1 = std::max(j1, j + 1);
            }
    }
    terrain.ensure(i0, i1, j0, j1);
    if (released != nullptr) *released = i1 > i0 ? ActiveBox{i0, i1, j0, j1} : ActiveBox{};
    // The momenta of released cells are written too (zeros, as they were): the first step
    // writes them anyway, and touched here their memory's first touch is the setup's, not
    // the time loop's.
    for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i)
            if (thickness(i, j) != 0.0) {
                s.h(i, j) = thickness(i, j) / terrain.normal_thickness(i, j);
                s.hu(i, j) = s.hv(i, j) = 0.0;
            }
    return s;
}

}  // namespace avalanche
