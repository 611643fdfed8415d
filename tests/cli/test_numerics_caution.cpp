// A run whose numerics the verification found unsound says so in one warning line
// (execute_scene.cpp, numerics_caution): Godunov with Savage-Hutter pressure advecting
// at Courant 0.2 or more (docs/verification.md, finding 2). The defaults, WAF at any
// Courant number and Godunov at its default Courant number run without it.
#include <gtest/gtest.h>

#include <string>

#include "cli_test_support.hpp"

namespace avalanche {
namespace {

std::string log_of(const test::ScratchDir& dir, const std::string& flags) {
    const std::string scenario = dir.write("scenario.toml", test::kSmallChute);
    static int k = 0;
    const std::string out = dir.file("out" + std::to_string(k++));
    const test::ProcessResult r =
        test::run_binary(dir, "run --scenario '" + scenario + "' --out '" + out +
                                  "' --t-end 0.2 --output-interval 0.1 " + flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out + r.err;
}

constexpr const char* kCaution = "numerics: Godunov advecting at Courant";

TEST(NumericsCaution, GodunovAdvectingAtCourantPointTwoIsWarnedOfOnce) {
    test::ScratchDir dir("caution");
    const std::string log = log_of(dir, "--scheme godunov --cfl 0.4");
    const auto at = log.find(std::string(kCaution) + " 0.2 (cfl 0.4, L S L)");
    ASSERT_NE(at, std::string::npos) << log;
    EXPECT_EQ(log.find(kCaution, at + 1), std::string::npos);  // one line
    EXPECT_NE(log.find("docs/verification.md, finding 2"), std::string::npos);
}

TEST(NumericsCaution, DefaultsAndWafRunWithoutIt) {
    test::ScratchDir dir("no_caution");
    for (const char* flags :
         {"", "--scheme godunov", "--scheme godunov --cfl 0.3", "--cfl 0.4", "--quality draft",
          "--scheme godunov --cfl 0.4 --earth-pressure isotropic"}) {
        SCOPED_TRACE(flags);
        EXPECT_EQ(log_of(dir, flags).find(kCaution), std::string::npos);
    }
}

}  // namespace
}  // namespace avalanche
