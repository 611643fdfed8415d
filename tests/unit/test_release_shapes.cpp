// The analytic release shapes rasterised as cell averages (physics/release.cpp): the
// rasterisation samples only the cells over the shape's extent, so it must give, bit
// for bit, the 8 x 8 sub-sample average of release_thickness_at over every cell of the
// grid, for shapes inside the grid, across its edges, on cell edges and outside it.
#include <gtest/gtest.h>

#include <vector>

#include "avalanche/physics/release.hpp"

using namespace avalanche;

namespace {

// The cell average by its definition: 8 x 8 sub-samples at the sub-cell centres, rows
// summed in the mirror pairs the rasterisation uses (so equal sums mean equal bits).
double cell_average(const ReleaseShape& r, const Grid& g, int i, int j) {
    constexpr int n = 8;
    const auto row_sum = [&](int b) {
        const double y = g.y0 + (j + (b + 0.5) / n) * g.dy;
        double sum = 0.0;
        for (int a = 0; a < n; ++a)
            sum += release_thickness_at(r, g.x0 + (i + (a + 0.5) / n) * g.dx, y);
        return sum;
    };
    double sum = 0.0;
    for (int b = 0; b < n / 2; ++b) sum += row_sum(b) + row_sum(n - 1 - b);
    return sum / (n * n);
}

}  // namespace

TEST(ReleaseShapes, RasterisedCellsAreTheSubSampleAverageOverTheWholeGrid) {
    const Grid g{40, 30, 0.5, 0.5, -3.0, 2.0};  // x in [-3, 17], y in [2, 17]
    const std::vector<ReleaseShape> shapes = {
        CapRelease{{5.0, 9.0}, 2.5},                // inside
        CapRelease{{-2.0, 3.0}, 2.5},               // across the south-west corner
        ParaboloidRelease{{16.5, 10.0}, 3.0, 2.0},  // across the east edge
        ParaboloidRelease{{4.75, 9.25}, 1.0, 1.0},  // centred on a cell corner
        BoxRelease{{1.0, 4.0}, {5.0, 6.5}, 1.5},    // edges on cell edges
        BoxRelease{{30.0, 40.0}, {5.0, 6.0}, 1.0},  // outside the grid
    };
    for (std::size_t k = 0; k < shapes.size(); ++k) {
        SCOPED_TRACE(k);
        const Field2D f = rasterize_release(shapes[k], g);
        int wet = 0, differ = 0;
        for (int j = 0; j < g.ny; ++j)
            for (int i = 0; i < g.nx; ++i) {
                const double expected = cell_average(shapes[k], g, i, j);
                differ += f(i, j) != expected;
                wet += expected > 0.0;
            }
        EXPECT_EQ(differ, 0);
        EXPECT_EQ(wet > 0, k + 1 < shapes.size());  // only the last lies outside
        EXPECT_EQ(f(-1, 0), 0.0);                   // ghosts stay zero
    }
}
