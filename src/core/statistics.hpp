#pragma once
// Mean and (population) standard deviation of a sample, NaN for an empty one: the figures every
// report prints as "mean ± std"; the median, which a few far-off trials do not move.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace mimic {

inline double mean_of(const std::vector<double>& v) {
  return v.empty() ? std::nan("") : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

inline double std_of(const std::vector<double>& v) {
  const double m = mean_of(v);
  double ss = 0;
  for (double x : v) ss += (x - m) * (x - m);
  return v.empty() ? std::nan("") : std::sqrt(ss / static_cast<double>(v.size()));
}

// The middle value (the mean of the two middle ones for an even count); NaN for an empty sample.
inline double median_of(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2) return *mid;
  return (*mid + *std::max_element(v.begin(), mid)) / 2;
}

}  // namespace mimic
