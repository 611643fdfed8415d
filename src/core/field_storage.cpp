#include "avalanche/core/field_storage.hpp"

#include <cstdint>
#include <cstdlib>
#include <cstring>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace avalanche {

namespace {

#if defined(__linux__)
// A large array's mapping: its bytes rounded up to whole pages.
std::size_t mapped_bytes(std::size_t bytes) { return (bytes + 4095) / 4096 * 4096; }
#endif

}  // namespace

void* allocate_field_bytes(std::size_t bytes) {
#if defined(__linux__)
    if (bytes >= kHugePageMinBytes) {
        // Over-map by one huge page, then give back what lies before the first 2 MiB
        // boundary and after the array: the mapping starts on the boundary and is zero.
        const std::size_t size = mapped_bytes(bytes);
        void* raw = mmap(nullptr, size + kHugePageBytes, PROT_READ | PROT_WRITE,
                         MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (raw == MAP_FAILED) throw std::bad_alloc();
        const auto base = reinterpret_cast<std::uintptr_t>(raw);
        const std::uintptr_t aligned = (base + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
        if (aligned > base) munmap(raw, aligned - base);
        const std::uintptr_t end = base + size + kHugePageBytes;
        if (end > aligned + size) munmap(reinterpret_cast<void*>(aligned + size), end - (aligned + size));
        void* p = reinterpret_cast<void*>(aligned);
#if defined(MADV_NOHUGEPAGE)
        // Small pages until advise_written_whole, also where THP is "always".
        (void)madvise(p, size, MADV_NOHUGEPAGE);
#endif
        return p;
    }
#endif
    const bool huge = bytes >= kHugePageMinBytes;  // only where mmap is not used
    void* p = nullptr;
    if (posix_memalign(&p, huge ? kHugePageBytes : 64, bytes == 0 ? 64 : bytes) != 0)
        throw std::bad_alloc();
    std::memset(p, 0, bytes);
    return p;
}

void* allocate_page_bytes(std::size_t bytes) {
#if defined(__linux__)
    if (bytes < kPageMappedMinBytes) return allocate_field_bytes(bytes);
    const std::size_t size = mapped_bytes(bytes);
    void* p = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
#if defined(MADV_NOHUGEPAGE)
    // Small pages also where THP is "always": a huge page would make the kernel zero
    // 2 MiB for the few columns written in it.
    if (size >= kHugePageBytes) (void)madvise(p, size, MADV_NOHUGEPAGE);
#endif
    return p;
#else
    return allocate_field_bytes(bytes);
#endif
}

void free_page_bytes(void* p, std::size_t bytes) noexcept {
    if (p == nullptr) return;
#if defined(__linux__)
    if (bytes < kPageMappedMinBytes) {
        free_field_bytes(p, bytes);
        return;
    }
    munmap(p, mapped_bytes(bytes));
#else
    free_field_bytes(p, bytes);
#endif
}

void advise_written_whole(void* p, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Only whole 2 MiB pages: the tail stays in small pages, so a field never holds more
    // than its own size plus under 2 MiB. A refusal (THP off) leaves small pages.
    if (p != nullptr && bytes >= kHugePageMinBytes)
        (void)madvise(p, bytes / kHugePageBytes * kHugePageBytes, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

void free_field_bytes(void* p, std::size_t bytes) noexcept {
    if (p == nullptr) return;
#if defined(__linux__)
    if (bytes >= kHugePageMinBytes) {
        munmap(p, mapped_bytes(bytes));
        return;
    }
#endif
    std::free(p);
}

}  // namespace avalanche
