#pragma once
// Items 0 .. n-1 shared out among a few threads, each taking the next one when it has
// finished its last: the scenarios of a batch (batch_run.cpp), the map files of a run
// (products.cpp).
#include <cstddef>
#include <functional>

namespace avalanche {

// Runs work(k) for every k in [0, items) on `workers` new threads (clamped to
// [1, items]) and returns when all have finished. on_start, if given, runs once in each
// thread before its first item. No thread takes a new item once stop() is true (if
// given) or once an item has thrown; the first exception is rethrown here after every
// thread has joined.
void run_on_threads(std::size_t items, int workers, const std::function<void(std::size_t)>& work,
                    const std::function<bool()>& stop = {},
                    const std::function<void()>& on_start = {});

}  // namespace avalanche
