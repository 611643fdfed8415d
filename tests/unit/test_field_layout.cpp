// The rows of a field (core/field.hpp): every row and its column 0 on a 64-byte cache
// line whatever the width, the ghost columns just before column 0 and after the last,
// and packed() / unpack() giving the cells without the rows' padding in the order of
// checkpoint files (row -ng first, column -ng first in each row).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "avalanche/core/field.hpp"

using namespace avalanche;

namespace {
std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }
// A value of its own for every cell (i, j), ghosts included.
double value_of(int i, int j) { return 1000.0 * j + i; }
}  // namespace

TEST(FieldLayout, EveryRowAndItsColumnZeroStartACacheLine) {
    for (const int nx : {1, 3, 6, 7, 8, 9, 200, 1000, 1001}) {
        for (const bool one_row : {false, true}) {
            const int ny = 5, ng = 2;
            const Field2D f =
                one_row ? Field2D::same_in_every_row(nx, ny, ng, 1.0) : Field2D(nx, ny, ng, 1.0);
            EXPECT_EQ(f.stride() % 8, 0) << nx;
            EXPECT_EQ(f.column0() % 8, 0) << nx;
            // Room for the ghost columns on both sides, less than a line of padding.
            EXPECT_GE(f.column0(), ng) << nx;
            EXPECT_GE(f.stride(), f.column0() + nx + ng) << nx;
            EXPECT_LT(f.stride(), f.column0() + nx + ng + 8) << nx;
            for (int j = -ng; j < ny + ng; ++j) {
                EXPECT_EQ(address(f.row(j)) % 64, 0u) << nx << " row " << j;
                // The ghost columns are the values just before and after the row's cells.
                EXPECT_EQ(f.index(-ng, j), f.index(0, j) - ng);
                EXPECT_EQ(f.index(nx + ng - 1, j), f.index(0, j) + nx + ng - 1);
            }
        }
    }
}

TEST(FieldLayout, PackedHoldsEveryCellGhostsIncludedRowByRow) {
    const int nx = 11, ny = 4, ng = 2;
    Field2D f(nx, ny, ng);
    for (int j = -ng; j < ny + ng; ++j)
        for (int i = -ng; i < nx + ng; ++i) f(i, j) = value_of(i, j);
    const std::vector<double> p = f.packed();
    ASSERT_EQ(p.size(), f.packed_size());
    ASSERT_EQ(p.size(), static_cast<std::size_t>((nx + 2 * ng) * (ny + 2 * ng)));
    std::size_t k = 0;
    for (int j = -ng; j < ny + ng; ++j)
        for (int i = -ng; i < nx + ng; ++i) EXPECT_EQ(p[k++], value_of(i, j)) << i << ", " << j;

    // Back into another field, and into an array of flags in the field's layout.
    Field2D g(nx, ny, ng);
    g.set_packed(p);
    for (int j = -ng; j < ny + ng; ++j)
        for (int i = -ng; i < nx + ng; ++i) EXPECT_EQ(g(i, j), value_of(i, j));
    std::vector<std::int64_t> flags(p.size());
    for (std::size_t q = 0; q < flags.size(); ++q) flags[q] = static_cast<std::int64_t>(q % 4);
    std::vector<unsigned char> cells(f.raw().size(), 9);
    f.unpack(flags.data(), cells.data());
    EXPECT_EQ(f.packed<std::int64_t>(cells.data()), flags);
    // The padding is no cell: unpack leaves it as it was.
    EXPECT_EQ(cells[static_cast<std::size_t>(f.index(nx + ng - 1, 0) + 1)], 9);
}
