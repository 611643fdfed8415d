#pragma once
// How the strips of an advection are handed to its threads (advection.cpp).
//
// Each thread starts on its own share, consecutive strips [first, end), and claims
// them one after the other. A thread whose share is done takes the upper half of what
// is left of the thread with the most left, as its new share: on a machine whose cores
// run at different speeds (a VM's cores shared with other guests: one of case (a)'s two
// threads spent 1-39 % longer on its strips than the other, docs/performance.md) the
// faster core no longer waits for the slower one at the end of every advection.
//
// A share's strips form segments (advection.cpp): the first strip of a segment computes
// its stage rows afresh, and the first and last strips of a segment keep back the
// updated rows another segment reads (five at the inner end) until every segment is
// done. So a thread must know, when it claims a strip, whether its share ends within
// those rows. The strips after the one a thread claims (one, or more where strips are
// shorter than the rows held back: reset's `reserved`) are therefore reserved to it: a
// thief takes only the strips beyond, so a share that does not end among them goes on
// at least to the last of them, whatever is stolen later.
//
// For the tests that compare shares taken from another thread with one thread's run
// (Stepper::set_all_strips_to_first_thread), reset() can make thread 0 wait until every
// other thread has made its first claim: the others then begin by taking from it
// whatever the machine's load. Left to the scheduler, a loaded 2-core machine once
// ran 400 advections in which thread 0 did all its strips before thread 1 claimed one.
#include <condition_variable>
#include <mutex>
#include <span>
#include <vector>

namespace avalanche {

class StripClaims {
  public:
    struct Claim {
        int strip = -1;       // -1: nothing left anywhere
        bool starts = false;  // the first strip of a share (taken at the start or stolen)
        bool ends = false;    // the last strip of its share: no later strip follows it
        // The share's last strip where it is among the strips reserved after this one
        // (or is this one): then no thief can change it any more. -1 where it is not yet
        // fixed: it is then at least the last of the reserved strips.
        int share_last = -1;
    };

    // Thread t's share is [first[t], first[t + 1]); first.back() is the number of strips.
    // With first_waits, thread 0's first next() returns only once every other thread
    // has called next() (each thread must call it, as the advection's do). `reserved`
    // (at least 1) strips after each claimed one stay the claimer's.
    void reset(std::span<const int> first, bool first_waits = false, int reserved = 1);
    // The next strip for thread t (safe to call from every thread at once).
    [[nodiscard]] Claim next(int t);
    // Shares taken from another thread since the last reset.
    [[nodiscard]] int steals() const;

  private:
    struct Share {
        int next = 0, end = 0;
        bool fresh = true;  // nothing claimed from it yet
    };
    mutable std::mutex mutex_;
    std::condition_variable others_claimed_;
    std::vector<Share> shares_;
    // With first_waits_ only: per thread, next() called since the reset; and how many
    // threads other than 0 have called it.
    std::vector<char> has_claimed_;
    int claimed_ = 0;
    bool first_waits_ = false;
    int reserved_ = 1;
    int steals_ = 0;
};

}  // namespace avalanche
