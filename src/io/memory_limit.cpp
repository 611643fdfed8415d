#include "avalanche/io/memory_limit.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "avalanche/core/error.hpp"

namespace avalanche {

namespace {
constexpr const char* kOverride = "AVALANCHE_MAX_MEMORY_GB";
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
}  // namespace

MemoryLimit memory_limit() {
    if (const char* text = std::getenv(kOverride); text != nullptr && *text != '\0') {
        char* end = nullptr;
        const double gib = std::strtod(text, &end);
        if (end == text || *end != '\0' || !std::isfinite(gib) || gib <= 0.0)
            throw ConfigError(kOverride,
                              "expected a positive number of GiB, got '" + std::string(text) + "'");
        return {gib * kGiB, std::string("memory allowed by ") + kOverride};
    }
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        double kib = 0.0;
        if (key == "MemAvailable:" && meminfo >> kib && kib > 0.0)
            return {kib * 1024.0, std::string("available memory (MemAvailable; set ") + kOverride +
                                      " to override)"};
        meminfo.ignore(256, '\n');
    }
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && page > 0)
        return {static_cast<double>(pages) * static_cast<double>(page),
                std::string("physical memory (set ") + kOverride + " to override)"};
    return {8.0 * kGiB, std::string("the default limit (set ") + kOverride + " to override)"};
}

}  // namespace avalanche
