#pragma once
// How much memory a run may plan for: grids whose estimated solver state exceeds it are
// refused before anything of their size is allocated (docs/cli.md "Refusals").
#include <string>

namespace avalanche {

struct MemoryLimit {
    double bytes = 0.0;
    std::string source;  // for messages: "available memory (MemAvailable; ...)"
};

// AVALANCHE_MAX_MEMORY_GB (GiB) when set -- a user who knows better, or a test; else
// the memory the kernel says can be allocated now without swapping (MemAvailable:
// free memory plus reclaimable caches); else the physical memory. Throws
// ConfigError("AVALANCHE_MAX_MEMORY_GB") for a malformed override.
MemoryLimit memory_limit();

// Estimated solver state per cell (bytes): state, terrain coefficients, observers'
// maps and the writers' buffers, with ghost cells; the DEM ingestion uses the same.
inline constexpr double kSolverBytesPerCell = 200.0;

}  // namespace avalanche
