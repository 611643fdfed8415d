#pragma once
// The GDAL-style text progress bar "0...10...20...30...40...50...60...70...80...90...100 - done."
// (one character per 2.5 %), written only when stderr is a terminal, so logs and pipes
// stay clean. Our own few lines: linking GDAL for this is not worth it.
#include <ostream>

namespace avalanche {

class TextProgressBar {
  public:
    explicit TextProgressBar(std::ostream& out) : out_(out) {}
    // Prints the ticks up to `fraction` (clamped to [0, 1]); never goes backwards.
    void update(double fraction);

  private:
    std::ostream& out_;
    int ticks_done_ = -1;  // ticks printed so far, 0..40
};

}  // namespace avalanche
