#include "logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace avalanche::detail {

void configure_logging(Verbosity v) {
    // One logger for the process; in-process callers (tests) call run_cli many times.
    static const auto logger = [] {
        auto l = spdlog::stderr_color_mt("avalanche-hazard");
        l->set_pattern("%^%l%$: %v");
        spdlog::set_default_logger(l);
        return l;
    }();
    switch (v) {
        case Verbosity::quiet:
            logger->set_level(spdlog::level::warn);
            break;
        case Verbosity::normal:
            logger->set_level(spdlog::level::info);
            break;
        case Verbosity::verbose:
            logger->set_level(spdlog::level::debug);
            break;
    }
}

}  // namespace avalanche::detail
