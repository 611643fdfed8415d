#pragma once
// Log lines go to stderr through spdlog ("info: ..."), so stdout carries only what a
// script may want to read (the version, where the results are).
#include <string>

namespace avalanche::detail {

enum class Verbosity { quiet, normal, verbose };

// (Re)configures the default logger; safe to call once per run_cli call.
void configure_logging(Verbosity v);

// While alive, every log line written by the calling thread starts with "[context] "
// (a batch names the scenario its worker thread runs, docs/batch.md). The context is
// per thread because batch scenarios run on parallel threads of one process; guards
// nest (the previous context comes back when a guard ends).
class ScopedLogContext {
  public:
    explicit ScopedLogContext(std::string context);
    ~ScopedLogContext();
    ScopedLogContext(const ScopedLogContext&) = delete;
    ScopedLogContext& operator=(const ScopedLogContext&) = delete;

  private:
    std::string previous_;
};

}  // namespace avalanche::detail
