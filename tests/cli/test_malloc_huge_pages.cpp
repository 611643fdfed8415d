// Huge pages for malloc's large buffers (malloc_huge_pages.hpp): when the CLI asks for
// them, and that a run's summary says whether they were in effect.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "avalanche/app/malloc_huge_pages.hpp"
#include "cli_test_support.hpp"

namespace avalanche {
namespace {

TEST(MallocHugePages, AskedOnlyInMadviseModeAndOnlyOnce) {
    const std::string madvise = "always [madvise] never";
    EXPECT_TRUE(wants_malloc_huge_pages(madvise, "", ""));
    EXPECT_TRUE(wants_malloc_huge_pages(madvise, "glibc.malloc.arena_max=2", ""));
    EXPECT_FALSE(wants_malloc_huge_pages("[always] madvise never", "", ""));
    EXPECT_FALSE(wants_malloc_huge_pages("always madvise [never]", "", ""));
    EXPECT_FALSE(wants_malloc_huge_pages("", "", ""));  // no such file: not Linux, or no THP
    EXPECT_FALSE(wants_malloc_huge_pages(madvise, "glibc.malloc.hugetlb=0", ""));  // the user's choice
    EXPECT_FALSE(wants_malloc_huge_pages(madvise, "", "0"));  // opted out
    EXPECT_FALSE(wants_malloc_huge_pages(madvise, "", "1"));  // asked already
    EXPECT_EQ(tunables_with_huge_pages(""), "glibc.malloc.hugetlb=1");
    EXPECT_EQ(tunables_with_huge_pages("glibc.malloc.arena_max=2"),
              "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
}

std::string thp_mode() {
    std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(f, line);
    return line;
}

bool summary_says_huge_pages(const std::string& out) {
    std::ifstream f(out + "/summary.json");
    return nlohmann::json::parse(f).at("performance").at("malloc_huge_pages").get<bool>();
}

// The binary re-executes itself with the tunable where the kernel's mode is "madvise",
// and its summary says so; with AVALANCHE_HUGE_PAGES=0 it does not (in any mode).
TEST(MallocHugePages, ARunAsksForThemWhereTheKernelWaitsToBeAsked) {
    test::ScratchDir dir("huge_pages");
    const std::string scenario = dir.write("scenario.toml", test::kSmallChute);
    const bool madvise = thp_mode().find("[madvise]") != std::string::npos;
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    if (tunables != nullptr && std::string(tunables).find("glibc.malloc.hugetlb") != std::string::npos)
        GTEST_SKIP() << "GLIBC_TUNABLES already chooses: " << tunables;
    ASSERT_EQ(std::getenv("AVALANCHE_HUGE_PAGES"), nullptr);
    const std::string out = dir.file("out");
    const auto r = test::run_binary(dir, "-q run --scenario '" + scenario + "' --out '" + out + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(summary_says_huge_pages(out), madvise);
    ::setenv("AVALANCHE_HUGE_PAGES", "0", 1);
    const std::string off = dir.file("off");
    const auto r0 = test::run_binary(dir, "-q run --scenario '" + scenario + "' --out '" + off + "'");
    ::unsetenv("AVALANCHE_HUGE_PAGES");
    ASSERT_EQ(r0.exit_code, 0) << r0.err;
    EXPECT_FALSE(summary_says_huge_pages(off));
}

}  // namespace
}  // namespace avalanche
