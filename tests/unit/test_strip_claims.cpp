// StripClaims (strip_claims.hpp): how an advection's threads claim strips, and take
// half of what another thread has left once their own share is done.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "avalanche/numerics/strip_claims.hpp"

namespace avalanche {
namespace {

struct Seen {
    int strip;
    bool starts, ends;
};

bool operator==(const Seen& a, const StripClaims::Claim& b) {
    return a.strip == b.strip && a.starts == b.starts && a.ends == b.ends;
}

// Without taking: each thread's share in order, its first strip starting it and its
// last ending it; then nothing.
TEST(StripClaims, EachThreadClaimsItsShareInOrder) {
    StripClaims c;
    c.reset(std::vector<int>{0, 3, 5});
    EXPECT_TRUE((Seen{0, true, false} == c.next(0)));
    EXPECT_TRUE((Seen{3, true, false} == c.next(1)));
    EXPECT_TRUE((Seen{1, false, false} == c.next(0)));
    EXPECT_TRUE((Seen{4, false, true} == c.next(1)));
    EXPECT_TRUE((Seen{2, false, true} == c.next(0)));
    // Both shares done; thread 1 finds nothing to take: the strip thread 0 claimed last
    // ended its share.
    EXPECT_EQ(c.next(1).strip, -1);
    EXPECT_EQ(c.next(0).strip, -1);
    EXPECT_EQ(c.steals(), 0);
}

// A thread with nothing left takes the upper half (rounded up) of the strips beyond the
// one the thread with the most left claims next: that one stays its owner's.
TEST(StripClaims, ATakerLeavesTheOwnersNextStrip) {
    StripClaims c;
    c.reset(std::vector<int>{0, 10, 10});  // every strip to thread 0
    EXPECT_TRUE((Seen{0, true, false} == c.next(0)));  // next is 1; 2 .. 9 beyond it
    EXPECT_TRUE((Seen{6, true, false} == c.next(1)));  // took 6 .. 9, half of the 8
    EXPECT_EQ(c.steals(), 1);
    // Thread 0 goes on from 1 and its share now ends at 5.
    for (int k = 1; k < 5; ++k) EXPECT_TRUE((Seen{k, false, false} == c.next(0))) << k;
    // After 4 thread 0's next is 5, the end of its share.
    EXPECT_TRUE((Seen{5, false, true} == c.next(0)));
    // Thread 1 claimed 6: 7 is reserved to it and 8, 9 lie beyond; thread 0 takes 9.
    EXPECT_TRUE((Seen{9, true, true} == c.next(0)));
    EXPECT_TRUE((Seen{7, false, false} == c.next(1)));
    EXPECT_TRUE((Seen{8, false, true} == c.next(1)));  // its share now ends at 8
    EXPECT_EQ(c.next(1).strip, -1);
    EXPECT_EQ(c.next(0).strip, -1);
    EXPECT_EQ(c.steals(), 2);
}

// One strip beyond an owner's next is taken too; the owner's next is not.
TEST(StripClaims, OneStripBeyondTheNextIsTakenTheNextIsNot) {
    StripClaims c;
    c.reset(std::vector<int>{0, 3, 3});
    EXPECT_TRUE((Seen{0, true, false} == c.next(0)));  // next 1, strip 2 beyond
    EXPECT_TRUE((Seen{2, true, true} == c.next(1)));
    EXPECT_TRUE((Seen{1, false, true} == c.next(0)));  // its share now ends at 1
    EXPECT_EQ(c.next(1).strip, -1);  // 1 was thread 0's next: nothing beyond it
    EXPECT_EQ(c.next(0).strip, -1);
    EXPECT_EQ(c.steals(), 1);
}

// With more strips reserved after each claim (short strips, whose segments hold back
// rows over several of them), a taker leaves them all to the owner, and a claim names
// its share's last strip once that is among them.
TEST(StripClaims, ATakerLeavesEveryStripReservedAfterTheOwnersClaim) {
    StripClaims c;
    c.reset(std::vector<int>{0, 10, 10}, false, 3);  // every strip to thread 0
    StripClaims::Claim k = c.next(0);                // 1 .. 3 reserved, 4 .. 9 beyond
    EXPECT_TRUE((Seen{0, true, false} == k));
    EXPECT_EQ(k.share_last, -1);  // 4 .. 9, beyond the reserved strips, may still be taken
    k = c.next(1);                // takes 7 .. 9, half of the six beyond
    EXPECT_TRUE((Seen{7, true, false} == k));
    EXPECT_EQ(k.share_last, 9);  // 8 and 9 are reserved to it now
    EXPECT_EQ(c.steals(), 1);
    for (int strip = 1; strip <= 6; ++strip) {
        k = c.next(0);
        EXPECT_TRUE((Seen{strip, false, strip == 6} == k)) << strip;
        // Thread 0's share ends at 6: named from the claim of 3 on (4 .. 6 reserved).
        EXPECT_EQ(k.share_last, strip >= 3 ? 6 : -1) << strip;
    }
    // Thread 1 claimed 7, so 8 and 9, all it has left, are reserved: nothing to take.
    EXPECT_EQ(c.next(0).strip, -1);
    EXPECT_TRUE((Seen{8, false, false} == c.next(1)));
    EXPECT_TRUE((Seen{9, false, true} == c.next(1)));
    EXPECT_EQ(c.next(1).strip, -1);
    EXPECT_EQ(c.steals(), 1);
}

// With first_waits (the tests' all-strips-to-the-first-thread runs), thread 0's first
// claim waits for every other thread's: here thread 1 takes half of thread 0's share
// before thread 0 claims a strip, however the two are scheduled.
TEST(StripClaims, TheFirstThreadWaitsForTheOthersFirstClaims) {
    StripClaims c;
    c.reset(std::vector<int>{0, 10, 10, 10}, true);  // every strip to thread 0
    std::atomic<bool> returned{false};
    StripClaims::Claim first_of_0;
    std::thread zero([&] {
        first_of_0 = c.next(0);
        returned = true;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(returned);  // two threads have not claimed yet
    EXPECT_TRUE((Seen{5, true, false} == c.next(1)));  // half of 1 .. 9 beyond 0
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(returned);  // thread 2 has not
    // Thread 0 has 1 .. 4 beyond its next, thread 1 has 7 .. 9: thread 2 takes 3, 4.
    EXPECT_TRUE((Seen{3, true, false} == c.next(2)));
    zero.join();
    EXPECT_TRUE((Seen{0, true, false} == first_of_0));
    EXPECT_EQ(c.steals(), 2);
    // Without it, thread 0 claims at once.
    c.reset(std::vector<int>{0, 10, 10, 10});
    EXPECT_TRUE((Seen{0, true, false} == c.next(0)));
    EXPECT_EQ(c.steals(), 0);
}

// Threads claiming at once: every strip is claimed exactly once; each thread's claims
// come as runs of consecutive strips, each run opened by a claim that starts it and
// closed by one that ends it, and a claim that does not end its run is followed by the
// same thread's claim of the next strip; a claim's share_last, where it names one, is
// its run's last strip, and where it does not the run goes on at least to the last
// strip reserved after it (the guarantees the advection's segments need). With 1 and 3
// strips reserved after each claim.
TEST(StripClaims, ConcurrentClaimsCoverEveryStripOnceInRuns) {
    constexpr int kStrips = 200, kThreads = 4;
    int taken_from_the_first = 0;
    for (int round = 0; round < 20; ++round) {
        const int reserved = round % 4 < 2 ? 1 : 3;
        StripClaims c;
        // Even rounds: every strip to thread 0, which waits for the others' first claims
        // (so each of them takes a share from it first, however the threads are
        // scheduled); odd rounds: even shares, thread 0 the slowest.
        std::vector<int> first{0, kStrips, kStrips, kStrips, kStrips};
        if (round % 2) first = {0, 50, 100, 150, kStrips};
        c.reset(first, round % 2 == 0, reserved);
        std::vector<std::vector<StripClaims::Claim>> got(kThreads);
        std::vector<std::thread> team;
        for (int t = 0; t < kThreads; ++t)
            team.emplace_back([&, t] {
                for (StripClaims::Claim k = c.next(t); k.strip >= 0; k = c.next(t)) {
                    got[static_cast<std::size_t>(t)].push_back(k);
                    // Thread 0 is the slow core: the others must take from it.
                    if (t == 0)
                        std::this_thread::sleep_for(std::chrono::microseconds(20));
                    else
                        std::this_thread::yield();
                }
            });
        for (auto& th : team) th.join();
        if (round % 2 == 0) taken_from_the_first += c.steals();
        std::vector<int> count(kStrips, 0);
        for (const auto& claims : got) {
            bool open = false;
            for (std::size_t q = 0; q < claims.size(); ++q) {
                const StripClaims::Claim& k = claims[q];
                ++count[static_cast<std::size_t>(k.strip)];
                EXPECT_EQ(k.starts, !open) << "round " << round << " strip " << k.strip;
                if (open) {
                    EXPECT_EQ(k.strip, claims[q - 1].strip + 1) << "round " << round;
                }
                open = !k.ends;
            }
            EXPECT_FALSE(open) << "round " << round;  // every run ended
            // Each claim's share_last against the run it belongs to.
            for (std::size_t q = 0; q < claims.size();) {
                std::size_t e = q;
                while (!claims[e].ends) ++e;  // the run's last claim
                for (std::size_t p = q; p <= e; ++p) {
                    const StripClaims::Claim& k = claims[p];
                    if (k.share_last >= 0) {
                        EXPECT_EQ(k.share_last, claims[e].strip) << "round " << round;
                    } else {
                        EXPECT_GE(claims[e].strip, k.strip + reserved) << "round " << round;
                    }
                }
                q = e + 1;
            }
        }
        EXPECT_TRUE(std::all_of(count.begin(), count.end(), [](int n) { return n == 1; }))
            << "round " << round;
    }
    // The runs checked include taken shares: in each of the ten rounds that give every
    // strip to thread 0, its three partners took one at least.
    EXPECT_GE(taken_from_the_first, 30);
}

}  // namespace
}  // namespace avalanche
