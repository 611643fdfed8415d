#include <gtest/gtest.h>

#include <sstream>

#include "avalanche/app/progress_bar.hpp"

namespace avalanche {
namespace {

TEST(TextProgressBar, PrintsTheGdalBarOnceWhateverTheUpdates) {
    std::ostringstream out;
    TextProgressBar bar(out);
    bar.update(0.0);
    EXPECT_EQ(out.str(), "0");
    bar.update(0.26);
    EXPECT_EQ(out.str(), "0...10...20..");
    bar.update(0.1);  // never backwards
    EXPECT_EQ(out.str(), "0...10...20..");
    bar.update(1.0);
    bar.update(1.0);
    EXPECT_EQ(out.str(), "0...10...20...30...40...50...60...70...80...90...100 - done.\n");
}

}  // namespace
}  // namespace avalanche
