#pragma once
// Resident memory of the test process, for the tests that check that memory a run never
// writes is never made (fields and maps of zeros on a large grid).
#include <cstdio>

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

}  // namespace avalanche::test
