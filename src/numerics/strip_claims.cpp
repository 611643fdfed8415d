#include "avalanche/numerics/strip_claims.hpp"

#include <algorithm>

namespace avalanche {

void StripClaims::reset(std::span<const int> first, bool first_waits, int reserved) {
    const std::lock_guard lock(mutex_);
    reserved_ = std::max(reserved, 1);
    shares_.clear();
    for (std::size_t t = 0; t + 1 < first.size(); ++t) shares_.push_back({first[t], first[t + 1], true});
    has_claimed_.assign(first_waits ? shares_.size() : 0, 0);  // read only with first_waits
    claimed_ = 0;
    first_waits_ = first_waits;
    steals_ = 0;
}

StripClaims::Claim StripClaims::next(int t) {
    std::unique_lock lock(mutex_);
    if (first_waits_ && !has_claimed_[static_cast<std::size_t>(t)]) {
        has_claimed_[static_cast<std::size_t>(t)] = 1;
        const auto others = static_cast<int>(shares_.size()) - 1;
        if (t != 0) {
            if (++claimed_ == others) others_claimed_.notify_one();
        } else {
            others_claimed_.wait(lock, [&] { return claimed_ == others; });
        }
    }
    Share& own = shares_[static_cast<std::size_t>(t)];
    if (own.next >= own.end) {
        // Steal: the upper half (rounded up) of the strips of the thread with the most
        // left beyond those reserved to it (the `reserved_` after its last claim, the
        // first of which it claims next; see the header). Also a single such strip: its
        // share of one strip recomputes about half a strip of stage rows and keeps all its
        // rows back, but its owner ends a strip sooner while the thief would only wait.
        std::size_t victim = shares_.size();
        int most = 0;
        for (std::size_t v = 0; v < shares_.size(); ++v) {
            const int beyond = shares_[v].end - shares_[v].next - reserved_;
            if (beyond > most) {
                most = beyond;
                victim = v;
            }
        }
        if (victim == shares_.size()) return {};
        Share& from = shares_[victim];
        const int split = from.end - (most + 1) / 2;
        own = {split, from.end, true};
        from.end = split;
        ++steals_;
    }
    Claim c;
    c.strip = own.next++;
    c.starts = own.fresh;
    c.ends = own.next == own.end;
    if (own.end - 1 <= c.strip + reserved_) c.share_last = own.end - 1;
    own.fresh = false;
    return c;
}

int StripClaims::steals() const {
    const std::lock_guard lock(mutex_);
    return steals_;
}

}  // namespace avalanche
