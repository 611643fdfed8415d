#pragma once
// SIGINT/SIGTERM during a run: the handler only sets a flag (nothing else is
// async-signal-safe); the progress callback reads it and stops the time loop after the
// current step, the loop writes DIR/checkpoint.h5, the outputs so far are written marked
// incomplete, and the run exits with ExitCode::interrupted (`run --resume DIR` goes on).
// The previous handlers come back when the guard ends.
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
