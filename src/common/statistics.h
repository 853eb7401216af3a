// Order statistics of measurement series (benchmarks, frame times, reload timelines).
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace wb {

// The p-quantile (0..1) by the nearest rank; 0 for an empty series.
inline double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5));
  return v[i];
}

// The median (the upper one of an even count); 0 for an empty series.
inline double median(std::vector<double> v) {
  return percentile(std::move(v), 0.5);
}

}  // namespace wb
