#pragma once
// Mean and (population) standard deviation of a sample, NaN for an empty one: the figures every
// report prints as "mean ± std".
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

}  // namespace mimic
