#include "avalanche/core/field_storage.hpp"

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace avalanche {

namespace {

// Large fields start at staggered offsets from their 2 MiB boundary. Fields on huge
// pages that all start on such a boundary share their physical address bits up to
// 2 MiB, so cell k of every field falls in the same L1 and L2 cache set; the 20-odd
// fields a step reads at one cell then evict each other (measured: benchmark (d)'s run
// took twice as long). Steps of 2 KiB + 64 B over 32 fields spread them over 64 KiB.
constexpr std::size_t kStaggerStep = 2048 + 64;
constexpr std::size_t kStaggerCount = 32;
constexpr std::size_t kHeader = 64;  // holds the base pointer; keeps 64-byte alignment
std::atomic<std::size_t> next_stagger{0};

}  // namespace

void* allocate_field_bytes(std::size_t bytes) {
    if (bytes < kHugePageMinBytes) {
        void* base = nullptr;
        if (posix_memalign(&base, kHeader, kHeader + bytes) != 0) throw std::bad_alloc();
        std::memcpy(base, &base, sizeof base);
        return static_cast<char*>(base) + kHeader;
    }
    const std::size_t offset =
        kHeader +
        kStaggerStep * (next_stagger.fetch_add(1, std::memory_order_relaxed) % kStaggerCount);
    const std::size_t total = offset + bytes;
    void* base = nullptr;
    if (posix_memalign(&base, kHugePageBytes, total) != 0) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Only whole 2 MiB pages: the tail stays in small pages, so a field never holds
    // more than its own size plus under 2 MiB. A refusal (THP off) leaves small pages.
    (void)madvise(base, total / kHugePageBytes * kHugePageBytes, MADV_HUGEPAGE);
#endif
    char* p = static_cast<char*>(base) + offset;
    std::memcpy(p - kHeader, &base, sizeof base);
    return p;
}

void free_field_bytes(void* p) noexcept {
    if (!p) return;
    void* base = nullptr;
    std::memcpy(&base, static_cast<char*>(p) - kHeader, sizeof base);
    std::free(base);
}

}  // namespace avalanche
