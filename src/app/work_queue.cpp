#include "work_queue.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace avalanche {

void run_on_threads(std::size_t items, int workers, const std::function<void(std::size_t)>& work,
                    const std::function<bool()>& stop, const std::function<void()>& on_start) {
    if (items == 0) return;
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex failure_mutex;
    std::exception_ptr failure;
    const auto worker = [&] {
        if (on_start) on_start();
        for (std::size_t k; !failed && !(stop && stop()) && (k = next++) < items;) {
            try {
                work(k);
            } catch (...) {
                const std::lock_guard lock(failure_mutex);
                if (!failure) failure = std::current_exception();
                failed = true;
            }
        }
    };
    const auto n = static_cast<std::size_t>(std::max(1, workers));
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < std::min(n, items); ++t) threads.emplace_back(worker);
    for (std::thread& t : threads) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace avalanche
