// libFuzzer harness: any bytes as a monitoring-point CSV file (gis::parse_points_csv, the
// parser behind read_points). A refusal is an InputError with a one-line message naming
// the file; a parsed point has a non-empty name and finite coordinates.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "avalanche/core/error.hpp"
#include "avalanche/gis/points.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        for (const auto& p : avalanche::gis::parse_points_csv(text, "fuzz.csv"))
            if (p.name.empty() || !std::isfinite(p.x) || !std::isfinite(p.y)) std::abort();
    } catch (const avalanche::InputError& e) {
        const std::string what = e.what();
        if (what.rfind("fuzz.csv: ", 0) != 0 || what.find('\n') != std::string::npos) std::abort();
    }
    return 0;
}
