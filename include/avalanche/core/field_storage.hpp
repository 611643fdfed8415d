#pragma once
// Storage of the grid-sized fields (Field2D, the regime flags).
//
// Every array comes zeroed, and an element made without a value (std::vector's
// value-initialisation: CellVector<double>(n), resize) is not written: it keeps the
// zero. Large arrays are fresh anonymous mappings, zero without being written, so a
// field of zeros costs no memory until its cells are written -- on a large DEM the
// cells a small flow never reaches are never touched (docs/performance.md, "The
// terrain made where the flow goes"). Hence one rule: an array's elements made
// without a value are zero only if that memory was never used before, so a vector
// that shrank must be grown with a value (assign, resize(n, 0.0)), never resize(n).
//
// Page size. A large array starts on a 2 MiB boundary but is left in 4 KiB pages
// unless the code about to write it whole says so (advise_written_whole): a field the
// flow writes here and there (the state, the terrain made tile by tile) first touches
// a 4 KiB page per row it reaches, where a 2 MiB page would make the kernel zero 128
// rows of a 2000-column grid for each field -- on benchmark (d), a small release on a
// 2000 x 2000 DEM, the first tiles of terrain cost 0.1-0.2 s that way, its whole setup
// 0.05 s without. A field written whole (a value everywhere, a copy, the elevation) is
// offered for huge pages, where one fault and one zeroing per 2 MiB is cheapest (on
// the Firecracker VMs of 2026-12-02, the setup of a fully touched 2000 x 2000 grid
// took 0.38-1.5 s with them against 2.0-2.6 s without; docs/performance.md, "A new
// machine", and "Pages by how a field is written"). The values, and so the results,
// are the same to the bit either way.
#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace avalanche {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
inline constexpr std::size_t kHugePageMinBytes = std::size_t{4} << 20;
inline constexpr std::size_t kPageMappedMinBytes = std::size_t{256} << 10;

// Zeroed bytes for a field, 64-byte aligned (a cache line, an AVX-512 vector); from
// kHugePageMinBytes on, a mapping of its own on a 2 MiB boundary, in small pages
// (Linux: advised so even where THP is "always") until advise_written_whole.
// Throws std::bad_alloc. Free with free_field_bytes and the same size.
void* allocate_field_bytes(std::size_t bytes);
void free_field_bytes(void* p, std::size_t bytes) noexcept;

// Says that the bytes [p, p + bytes) of an array from allocate_field_bytes are about to
// be written whole: an array of kHugePageMinBytes or more is offered to the kernel for
// transparent huge pages (madvise; only its whole 2 MiB pages, so the tail stays small).
// Call it before the first write: pages already touched stay as they are. Elsewhere
// than Linux, or where the kernel declines (THP off), nothing changes.
void advise_written_whole(void* p, std::size_t bytes) noexcept;

// Zeroed bytes for an array written only in part: from kPageMappedMinBytes on (Linux),
// a mapping of its own in small pages, so that it holds only the pages written; below,
// as allocate_field_bytes (the heap, zeroed). The advection's strip buffers are such
// arrays: grid-wide rows of which a small flow on a large DEM writes the few columns of
// its box (2 x 20 MB a run on an ASTER-size tile's 3601 columns, written whole before).
// Small arrays stay on the heap, whose pages a later run in the same process (a batch,
// a benchmark's repetitions) finds made: mapped afresh, the 30 arrays of 39 kB of a
// 200-column grid cost each run 600 page faults, 6-13 % of benchmark (d)'s crop.
// Free with free_page_bytes and the same size.
void* allocate_page_bytes(std::size_t bytes);
void free_page_bytes(void* p, std::size_t bytes) noexcept;

// Where an allocator's arrays come from: allocate_field_bytes (fields) or
// allocate_page_bytes (arrays written only in part).
enum class ZeroBytes { field, pages };

template <class T, ZeroBytes From = ZeroBytes::field>
struct FieldAllocator {
    static_assert(std::is_trivially_default_constructible_v<T>, "zero bytes must be a value of T");
    using value_type = T;
    template <class U>
    struct rebind {
        using other = FieldAllocator<U, From>;
    };
    FieldAllocator() = default;
    template <class U>
    FieldAllocator(const FieldAllocator<U, From>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
        const std::size_t bytes = n * sizeof(T);
        return static_cast<T*>(From == ZeroBytes::field ? allocate_field_bytes(bytes)
                                                        : allocate_page_bytes(bytes));
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if constexpr (From == ZeroBytes::field)
            free_field_bytes(p, n * sizeof(T));
        else
            free_page_bytes(p, n * sizeof(T));
    }
    // Value-initialisation leaves the allocation's zero bytes as they are (see above).
    template <class U>
    void construct(U* p) noexcept {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    template <class U>
    bool operator==(const FieldAllocator<U, From>&) const noexcept {
        return true;
    }
};

// A vector with one element per grid cell (a field's values, the regime flags).
template <class T>
using CellVector = std::vector<T, FieldAllocator<T>>;
using FieldStorage = CellVector<double>;
// A vector whose pages are made only where it is written (allocate_page_bytes); the
// same rule as above for elements made without a value.
template <class T>
using PageVector = std::vector<T, FieldAllocator<T, ZeroBytes::pages>>;

}  // namespace avalanche
