#pragma once
// Storage of the grid-sized fields (Field2D, the regime flags). Large arrays start
// on a 2 MiB boundary and are offered to the kernel for transparent huge pages
// (madvise), because on the project's virtual machines first touching a grid's memory
// 4 KiB page by 4 KiB page was most of the setup of a large scene: benchmark (d)'s
// 2000 x 2000 DEM spent about 2 of its 2.0-2.6 s of setup in page faults and zeroing,
// for a run of 0.06 s; with 2 MiB pages the setup took 0.38-1.5 s (docs/performance.md,
// "A new machine", "Setup of a large grid"). The values, and so the results, are the
// same to the bit.
// Arrays under kHugePageMinBytes stay in small pages.
#include <cstddef>
#include <new>
#include <vector>

namespace avalanche {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
inline constexpr std::size_t kHugePageMinBytes = std::size_t{4} << 20;

// Raw bytes for a field, 64-byte aligned (a cache line, an AVX-512 vector); from
// kHugePageMinBytes on, on a 2 MiB boundary and advised for huge pages (Linux;
// elsewhere, or where the kernel declines, the memory is ordinary). Throws
// std::bad_alloc. Free with free_field_bytes.
void* allocate_field_bytes(std::size_t bytes);
void free_field_bytes(void* p) noexcept;

template <class T>
struct FieldAllocator {
    using value_type = T;
    FieldAllocator() = default;
    template <class U>
    FieldAllocator(const FieldAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_field_bytes(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t) noexcept { free_field_bytes(p); }
    template <class U>
    bool operator==(const FieldAllocator<U>&) const noexcept {
        return true;
    }
};

// A vector with one element per grid cell (a field's values, the regime flags).
template <class T>
using CellVector = std::vector<T, FieldAllocator<T>>;
using FieldStorage = CellVector<double>;

}  // namespace avalanche
