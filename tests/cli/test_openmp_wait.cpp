// The CLI's choice of how OpenMP threads wait between parallel regions
// (openmp_wait.hpp): a short spin only when /proc/loadavg's runnable-task count says
// that nothing but the reader is runnable; sleeping otherwise and when it cannot be read.
#include <gtest/gtest.h>

#include <string>

#include "avalanche/app/openmp_wait.hpp"

namespace avalanche {
namespace {

TEST(OpenmpWait, SpinsOnlyWhenNothingElseIsRunnable) {
    const OpenmpWait alone = choose_openmp_wait("0.00 0.01 0.05 1/83 3243\n");
    EXPECT_EQ(alone.variable, "GOMP_SPINCOUNT");
    EXPECT_EQ(alone.value, "3000");
    for (const std::string busy : {"1.92 1.61 1.72 2/90 3300", "7.00 7.00 7.00 9/120 4000"}) {
        const OpenmpWait w = choose_openmp_wait(busy);
        EXPECT_EQ(w.variable, "OMP_WAIT_POLICY") << busy;
        EXPECT_EQ(w.value, "passive") << busy;
    }
    // The load averages themselves do not decide: a machine just left by another run.
    EXPECT_EQ(choose_openmp_wait("1.95 1.80 1.20 1/85 5000").variable, "GOMP_SPINCOUNT");
}

TEST(OpenmpWait, SleepsWhenTheLoadCannotBeRead) {
    for (const std::string bad : {"", "garbage", "0.1 0.2 0.3", "0.1 0.2 0.3 0/80 1", "0.1 0.2 0.3 1-80 1"})
        EXPECT_EQ(choose_openmp_wait(bad).value, "passive") << '"' << bad << '"';
}

}  // namespace
}  // namespace avalanche
