// Storage of grid-sized fields (core/field_storage.hpp): every array 64-byte aligned
// (the row kernels' vectors), large ones on a 2 MiB boundary (only whole huge pages
// can be advised), and the allocator interchangeable with std::vector's value
// semantics (copies, moves, assignment from ordinary vectors).
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "avalanche/core/field.hpp"
#include "support/resident_memory.hpp"

using namespace avalanche;

namespace {
std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }
}  // namespace

TEST(FieldStorage, ArraysAreAlignedAndLargeOnesStartOnAHugePage) {
    const std::size_t large = kHugePageMinBytes / sizeof(double) + 1000;
    std::vector<FieldStorage> fields;
    for (int k = 0; k < 8; ++k) fields.emplace_back(large, 1.5);
    fields.emplace_back(100, 2.5);  // small: the ordinary heap
    for (const FieldStorage& f : fields) {
        EXPECT_EQ(address(f.data()) % 64, 0u);
        if (f.size() == large) {
            EXPECT_EQ(address(f.data()) % kHugePageBytes, 0u);
        }
    }
    EXPECT_EQ(fields[3][large - 1], 1.5);
    EXPECT_EQ(fields[8][99], 2.5);
}

TEST(FieldStorage, FieldsCopyMoveAndTakeOrdinaryVectors) {
    Field2D a(1100, 1000, 2, 0.25);  // > kHugePageMinBytes
    a(5, 7) = 3.0;
    Field2D b = a;
    EXPECT_EQ(b(5, 7), 3.0);
    EXPECT_NE(b.raw().data(), a.raw().data());
    Field2D c = std::move(b);
    EXPECT_EQ(c(5, 7), 3.0);
    const std::vector<double> plain(a.raw().size(), -1.0);
    c.raw().assign(plain.begin(), plain.end());
    EXPECT_EQ(c(5, 7), -1.0);
    EXPECT_EQ(a(5, 7), 3.0);
    CellVector<std::int32_t> flags(5'000'000, 3);
    EXPECT_EQ(address(flags.data()) % 64, 0u);
    EXPECT_EQ(flags.back(), 3);
}

// Fields of zeros are zero without being written: a large one holds no memory until its
// cells are written (terrain made on demand, a state whose flow covers part of the grid),
// and small ones are zeroed by the allocator.
TEST(FieldStorage, ZeroFieldsAreZeroAndLargeOnesUntouchedUntilWritten) {
    const Field2D small(10, 10, 2);
    for (const double v : small.raw()) ASSERT_EQ(v, 0.0);
    const CellVector<std::int32_t> flags(1000);
    for (const std::int32_t v : flags) ASSERT_EQ(v, 0);
    const long long before = test::resident_bytes();
    if (before < 0) GTEST_SKIP() << "no /proc/self/statm";
    Field2D large(4000, 2000, 2);  // 64 MB
    large(10, 10) = 1.0;
    large(3999, 1999) = 2.0;
    const long long grown = test::resident_bytes() - before;
    EXPECT_LT(grown, 16ll << 20) << "a field of zeros was written";
    EXPECT_EQ(large(2000, 1000), 0.0);
    EXPECT_EQ(large(3999, 1999), 2.0);
    // Made with a value, every element is written.
    const Field2D ones(100, 100, 2, 1.0);
    EXPECT_EQ(ones(-2, -2), 1.0);
    EXPECT_EQ(ones(101, 101), 1.0);
}

namespace {
// The "THPeligible" line of /proc/self/smaps for the mapping holding p (Linux): 1 where
// the kernel may back it with huge pages, 0 where not, -1 if unknown (no smaps, an
// older kernel, or THP off on this machine).
int huge_page_eligible(const void* p) {
    std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string mode;
    if (!std::getline(thp, mode) || mode.find("[never]") != std::string::npos) return -1;
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        unsigned long long lo = 0, hi = 0;
        char dash = 0;
        std::istringstream head(line);
        if (head >> std::hex >> lo >> dash >> hi && dash == '-') {
            inside = address(p) >= lo && address(p) < hi;
        } else if (inside && line.rfind("THPeligible:", 0) == 0) {
            return std::stoi(line.substr(12));
        }
    }
    return -1;
}
}  // namespace

// A field written here and there (the state, terrain made tile by tile) holds a small
// page per row it reaches: with 2 MiB pages each row written would make the kernel zero
// 64 rows of this 4000-column field (field_storage.hpp). A field written whole (made
// with a value, filled, advised, or a copy) may take huge pages.
TEST(FieldStorage, OnlyFieldsWrittenWholeTakeHugePages) {
    const long long before = test::resident_bytes();
    if (before < 0) GTEST_SKIP() << "no /proc/self/statm";
    Field2D sparse(4000, 2000, 2);  // 64 MB, 32 kB per row
    for (int j = 0; j < 256; ++j) sparse(10, j) = 1.0;  // 256 small pages = 1 MiB
    const long long grown = test::resident_bytes() - before;
    EXPECT_LT(grown, 3ll << 20) << "rows written one cell each took huge pages";
    EXPECT_EQ(sparse(10, 255), 1.0);
    EXPECT_EQ(sparse(11, 255), 0.0);

    const int unadvised = huge_page_eligible(sparse.raw().data());
    const Field2D whole(4000, 2000, 2, 1.0);
    Field2D copied(4000, 2000, 2);
    copied.advise_written_whole();
    const int advised = huge_page_eligible(whole.raw().data());
    if (unadvised < 0 || advised < 0) GTEST_SKIP() << "THP off or not reported in /proc/self/smaps";
    EXPECT_EQ(unadvised, 0);
    EXPECT_EQ(advised, 1);
    EXPECT_EQ(huge_page_eligible(copied.raw().data()), 1);
    // A copy writes every cell, so it is advised too; and it holds the values.
    const Field2D copy = sparse;
    EXPECT_EQ(huge_page_eligible(copy.raw().data()), 1);
    EXPECT_EQ(copy(10, 255), 1.0);
    EXPECT_EQ(copy(11, 255), 0.0);
    Field2D assigned(10, 10, 2);
    assigned = sparse;
    EXPECT_EQ(huge_page_eligible(assigned.raw().data()), 1);
    EXPECT_EQ(assigned.nx(), 4000);
    EXPECT_EQ(assigned(10, 200), 1.0);
}

// Arrays written only in part (the advection's strip buffers: grid-wide rows of which a
// small flow writes a few columns) hold only the pages written, also below the size
// from which fields get mappings of their own (which the heap would hand out zeroed by
// writing them).
TEST(FieldStorage, PageVectorsAreZeroAndHoldOnlyThePagesWritten) {
    const long long before = test::resident_bytes();
    if (before < 0) GTEST_SKIP() << "no /proc/self/statm";
    constexpr std::size_t kRow = 4004, kRows = 24;  // 751 kB an array: the heap's size
    static_assert(kRow * kRows * sizeof(double) < kHugePageMinBytes);
    std::vector<PageVector<double>> arrays;
    for (int k = 0; k < 30; ++k) arrays.emplace_back(kRow * kRows);  // 22.5 MB in all
    for (PageVector<double>& a : arrays) {
        EXPECT_EQ(address(a.data()) % 4096, 0u);
        for (std::size_t r = 0; r < kRows; ++r) a[r * kRow + 2000] = 1.0;  // a page a row
    }
    const long long grown = test::resident_bytes() - before;
    EXPECT_LT(grown, 8ll << 20) << "arrays written in part were written whole";
    EXPECT_EQ(arrays[7][5 * kRow + 2000], 1.0);
    EXPECT_EQ(arrays[7][5 * kRow + 2001], 0.0);
    const PageVector<double> copy = arrays[3];
    EXPECT_EQ(copy[kRow + 2000], 1.0);
    EXPECT_EQ(copy[kRow + 1999], 0.0);
}
