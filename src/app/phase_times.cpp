#include "avalanche/app/phase_times.hpp"

#include <spdlog/fmt/fmt.h>

namespace avalanche {

double PhaseTimes::total() const {
    double sum = 0.0;
    for (const auto& [name, seconds] : phases_) sum += seconds;
    return sum;
}

nlohmann::json PhaseTimes::to_json() const {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [name, seconds] : phases_) out[name] = seconds;
    out["total"] = total();
    return out;
}

std::string PhaseTimes::describe() const {
    std::string out;
    for (const auto& [name, seconds] : phases_)
        out += fmt::format("{}{} {:.3g} s", out.empty() ? "" : ", ", name, seconds);
    return out + fmt::format(" (total {:.3g} s)", total());
}

}  // namespace avalanche
