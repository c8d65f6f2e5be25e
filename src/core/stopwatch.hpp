#pragma once
// Wall-clock seconds since a point in time (monotonic), for throughput and time-share figures.
#include <chrono>

namespace mimic {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mimic
