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
// its stage rows afresh, and the first and last strips of a segment keep their updated
// rows back until every segment is done, because another segment reads the state
// there. So a thread must know, when it claims a strip, whether the strip ends its
// share. The strip after the one a thread claims is therefore reserved to it: a thief
// takes only the strips beyond, so a claimed strip that does not end the share is
// followed by the same thread's next strip, whatever is stolen later.
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
    };

    // Thread t's share is [first[t], first[t + 1]); first.back() is the number of strips.
    void reset(std::span<const int> first);
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
    std::vector<Share> shares_;
    int steals_ = 0;
};

}  // namespace avalanche
