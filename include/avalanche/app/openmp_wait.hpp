#pragma once
// How libgomp's idle threads wait between parallel regions, chosen by the CLI when the
// user has not (OMP_WAIT_POLICY or GOMP_SPINCOUNT in the environment).
//
// The solver opens several parallel regions a step, often over small active areas.
// Threads that sleep between them (OMP_WAIT_POLICY=passive) pay a wake-up at every
// region: on avaKot at 5 m on two idle cores the time loop took 9.3 s against 7.9 s
// with a short spin (GOMP_SPINCOUNT=3000) and 7.5 s with a long one (30000). Threads
// that spin while another program holds a core steal it from the thread they wait
// for: with one core busy the same run took 12.4 s sleeping, 14.0 s with the short
// spin and 25.5 s with the long one (libgomp's own default, 300000 spins, was 5-90x
// slower there; docs/performance.md). So the short spin is chosen only when nothing
// else is runnable as the program starts, and sleeping otherwise.
#include <string>

namespace avalanche {

struct OpenmpWait {
    std::string variable;  // OMP_WAIT_POLICY or GOMP_SPINCOUNT
    std::string value;
};

// Spins between regions (GOMP_SPINCOUNT=3000) only if the runnable-task count of
// `loadavg` (the text of /proc/loadavg, "0.10 0.20 0.30 R/T last-pid"; R counts the
// reader) says that nothing else is runnable; OMP_WAIT_POLICY=passive otherwise and
// when the text cannot be read.
[[nodiscard]] OpenmpWait choose_openmp_wait(const std::string& loadavg);

// The wait in effect in this process, for the run summary: "passive", "active",
// "spin N" (GOMP_SPINCOUNT) or "default".
[[nodiscard]] std::string openmp_wait_in_effect();

}  // namespace avalanche
