#include "avalanche/app/malloc_huge_pages.hpp"

#include <cstdlib>

namespace avalanche {

namespace {
constexpr const char* kHugeTlb = "glibc.malloc.hugetlb";
}

bool wants_malloc_huge_pages(const std::string& thp_enabled, const std::string& tunables,
                             const std::string& asked) {
    if (!asked.empty()) return false;  // opted out, or asked already
    if (tunables.find(kHugeTlb) != std::string::npos) return false;  // the user's choice
    return thp_enabled.find("[madvise]") != std::string::npos;
}

std::string tunables_with_huge_pages(const std::string& tunables) {
    const std::string ours = std::string(kHugeTlb) + "=1";
    return tunables.empty() ? ours : tunables + ":" + ours;
}

bool malloc_huge_pages_in_effect() {
    const char* t = std::getenv("GLIBC_TUNABLES");
    return t != nullptr && std::string(t).find(std::string(kHugeTlb) + "=1") != std::string::npos;
}

}  // namespace avalanche
