#pragma once
// The "min" aggregate of Google Benchmark repetitions (ComputeStatistics("min", min_of)):
// the least disturbed repetition, which is what a shared, noisy machine can measure.
#include <algorithm>
#include <vector>

namespace avalanche::bench {

inline double min_of(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

}  // namespace avalanche::bench
