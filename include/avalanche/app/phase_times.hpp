#pragma once
// Wall time of a run's phases (reading and preparing the inputs, the solver, the
// products, the report), for the run summary and the log. On a large DEM most of a
// short run's wall time is outside the solver (docs/performance.md, "Outside the
// solver"); the summary's cell updates per second say nothing about it.
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace avalanche {

class PhaseTimes {
public:
    using Clock = std::chrono::steady_clock;

    // Starts the clock of the first lap.
    PhaseTimes() : lap_start_(Clock::now()) {}

    // Records a phase measured elsewhere (e.g. the scene's preparation by the caller).
    void add(std::string name, double seconds) { phases_.emplace_back(std::move(name), seconds); }
    // Records the time since the last lap (or since construction) as phase `name`.
    void lap(std::string name) {
        const Clock::time_point now = Clock::now();
        add(std::move(name), std::chrono::duration<double>(now - lap_start_).count());
        lap_start_ = now;
    }

    [[nodiscard]] double total() const;
    // {"<phase>": seconds, ..., "total": seconds}.
    [[nodiscard]] nlohmann::json to_json() const;
    // "prepare 2.31 s, simulate 1.98 s, ... (total 12.4 s)" for the log.
    [[nodiscard]] std::string describe() const;

private:
    Clock::time_point lap_start_;
    std::vector<std::pair<std::string, double>> phases_;
};

}  // namespace avalanche
