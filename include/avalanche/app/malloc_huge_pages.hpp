#pragma once
// Transparent huge pages for glibc's malloc, asked for by the CLI unless the user opts
// out (AVALANCHE_HUGE_PAGES=0) or has chosen (glibc.malloc.hugetlb in GLIBC_TUNABLES).
// The CLI sets AVALANCHE_HUGE_PAGES=1 with the tunable, so that the process it
// re-executes does not ask again (should a C library drop the tunable it does not know).
//
// A run on a large DEM allocates grid-sized buffers one after the other (the warped
// DEM, the void fill's rasters, the release, the products' maps and GDAL's copies of
// them), each written once, and on a kernel whose transparent huge pages are given
// only where a program asks ("madvise", Debian's default) every 4 KiB of them costs a
// page fault; in a VM that is a third of such a run (an ASTER-size tile: 6.95-7.63 s,
// 4.53-4.73 s with the tunable; docs/performance.md, "Huge pages for malloc's buffers"). glibc (2.35 and later) asks for
// them itself with the tunable glibc.malloc.hugetlb=1, which it reads only as the
// program starts: the CLI sets it in the re-execution it makes for the OpenMP wait
// (cli.cpp). The solver's own grid fields choose their pages themselves
// (field_storage.hpp), so the maps that hold memory only where the flow went still do.
#include <string>

namespace avalanche {

// Whether to ask: `thp_enabled` is the text of
// /sys/kernel/mm/transparent_hugepage/enabled (the mode in brackets), `tunables` the
// value of GLIBC_TUNABLES (empty if unset), `asked` the value of AVALANCHE_HUGE_PAGES
// (empty if unset; "0" opts out, "1" says the CLI has asked already). Only in "madvise"
// mode: with "always" malloc's memory gets them anyway, with "never" it cannot.
[[nodiscard]] bool wants_malloc_huge_pages(const std::string& thp_enabled, const std::string& tunables,
                                           const std::string& asked);

// GLIBC_TUNABLES with glibc.malloc.hugetlb=1 added to `tunables` (colon-separated).
[[nodiscard]] std::string tunables_with_huge_pages(const std::string& tunables);

// Whether this process's malloc asks for them (glibc.malloc.hugetlb=1 in its
// GLIBC_TUNABLES), for the run summary.
[[nodiscard]] bool malloc_huge_pages_in_effect();

}  // namespace avalanche
