#include "logging.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <string_view>
#include <utility>

namespace avalanche::detail {

namespace {

// The calling thread's context; the logger is synchronous, so the flag below is
// formatted on the thread that logs and sees that thread's value.
thread_local std::string t_log_context;

// "%*" in the pattern: "[context] " when the thread has a context, nothing otherwise.
class ContextFlag final : public spdlog::custom_flag_formatter {
  public:
    void format(const spdlog::details::log_msg&, const std::tm&,
                spdlog::memory_buf_t& dest) override {
        if (t_log_context.empty()) return;
        dest.push_back('[');
        dest.append(t_log_context.data(), t_log_context.data() + t_log_context.size());
        dest.append(std::string_view("] "));
    }
    [[nodiscard]] std::unique_ptr<custom_flag_formatter> clone() const override {
        return std::make_unique<ContextFlag>();
    }
};

}  // namespace

void configure_logging(Verbosity v) {
    // One logger for the process; in-process callers (tests) call run_cli many times.
    static const auto logger = [] {
        auto l = spdlog::stderr_color_mt("avalanche-hazard");
        auto formatter = std::make_unique<spdlog::pattern_formatter>();
        formatter->add_flag<ContextFlag>('*').set_pattern("%^%l%$: %*%v");
        l->set_formatter(std::move(formatter));
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

ScopedLogContext::ScopedLogContext(std::string context)
    : previous_(std::exchange(t_log_context, std::move(context))) {}

ScopedLogContext::~ScopedLogContext() { t_log_context = std::move(previous_); }

}  // namespace avalanche::detail
