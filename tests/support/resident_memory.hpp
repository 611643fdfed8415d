#pragma once
// Resident memory of the test process, for the tests that check that memory a run never
// writes is never made (fields and maps of zeros on a large grid); bench_runs reads it too
// (the process's own memory before a scene). Header-only: no test framework needed.
#include <cstddef>
#include <cstdio>

#if defined(__linux__)
#include <sys/mman.h>
#include <sys/resource.h>
#endif

namespace avalanche::test {

// Resident memory of this process in bytes (Linux /proc/self/statm), or -1.
inline long long resident_bytes() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (!f) return -1;
    long long pages = 0, resident = 0;
    const int n = std::fscanf(f, "%lld %lld", &pages, &resident);
    std::fclose(f);
    return n == 2 ? resident * 4096 : -1;
}

// Minor page faults of this process so far (getrusage), or -1. Unlike the resident
// memory, it counts a first read of an untouched page too (mapped to the zero page).
inline long minor_page_faults() {
#if defined(__linux__)
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_minflt;
#else
    return -1;
#endif
}

// Whether this kernel maps a read of an untouched anonymous page to the shared zero page
// (no memory made) -- the usual Linux behaviour. Some kernels give every read fault a
// page of its own (seen on a Firecracker guest, kernel 6.18): there a field of zeros read
// whole is resident whatever the program wrote, and a test of "read but never written"
// cannot tell the two apart. Probed on 8 MiB mapped as field_storage.cpp maps fields.
inline bool untouched_reads_stay_unmade() {
#if defined(__linux__)
    constexpr std::size_t bytes = std::size_t{8} << 20;
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) return false;
#if defined(MADV_NOHUGEPAGE)
    (void)madvise(p, bytes, MADV_NOHUGEPAGE);
#endif
    const long long before = resident_bytes();
    const volatile char* c = static_cast<const char*>(p);
    char sum = 0;
    for (std::size_t k = 0; k < bytes; k += 4096) sum = static_cast<char>(sum + c[k]);
    const long long grown = resident_bytes() - before;
    munmap(p, bytes);
    return sum == 0 && before >= 0 && grown < static_cast<long long>(bytes / 2);
#else
    return false;
#endif
}

}  // namespace avalanche::test
