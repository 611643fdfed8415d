#include "avalanche/app/progress_bar.hpp"

#include <algorithm>
#include <cmath>

namespace avalanche {

void TextProgressBar::update(double fraction) {
    constexpr int kTicks = 40;  // 2.5 % each, a number every fourth tick
    const double f = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
    const int target = static_cast<int>(std::floor(f * kTicks + 1e-9));
    if (target <= ticks_done_) return;
    for (int k = ticks_done_ + 1; k <= target; ++k) {
        if (k % 4 == 0)
            out_ << (k / 4) * 10;
        else
            out_ << '.';
    }
    ticks_done_ = target;
    if (ticks_done_ == kTicks) out_ << " - done.\n";
    out_.flush();
}

}  // namespace avalanche
