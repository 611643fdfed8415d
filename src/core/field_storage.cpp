#include "avalanche/core/field_storage.hpp"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace avalanche {

void* allocate_field_bytes(std::size_t bytes) {
    const bool huge = bytes >= kHugePageMinBytes;
    void* p = nullptr;
    if (posix_memalign(&p, huge ? kHugePageBytes : 64, bytes == 0 ? 64 : bytes) != 0)
        throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // Only whole 2 MiB pages: the tail stays in small pages, so a field never holds
    // more than its own size plus under 2 MiB. A refusal (THP off) leaves small pages.
    if (huge) (void)madvise(p, bytes / kHugePageBytes * kHugePageBytes, MADV_HUGEPAGE);
#endif
    return p;
}

void free_field_bytes(void* p) noexcept { std::free(p); }

}  // namespace avalanche
