#pragma once
// SIGINT/SIGTERM during a run: the handler only sets a flag; the progress callback
// reads it and stops the time loop, the outputs so far are written, and the run exits
// with ExitCode::interrupted. The previous handlers come back when the guard ends.
#include <csignal>

namespace avalanche::detail {

class InterruptGuard {
  public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    [[nodiscard]] static bool requested();

  private:
    void (*old_int_)(int);
    void (*old_term_)(int);
};

}  // namespace avalanche::detail
