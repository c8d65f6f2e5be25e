#pragma once
// The LibTorch side of `mimic bench policy`: a trained policy's mean actions and their cost, as
// the trainer computes them (observation normaliser, then the network), for comparison with the
// torch-free runtime. Free of LibTorch headers.
#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "core/stopwatch.hpp"
#include "learn/trainer/trainer.hpp"

namespace mimic {

// The policy's mean actions for raw inputs (rows), in one batch.
Eigen::MatrixXd libtorch_policy_actions(Trainer& trainer, const Eigen::MatrixXd& inputs);
// Microseconds per call of `act` (rows -> actions) on batches of `batch` rows taken in turn from
// `inputs`, over at least `seconds`, after a warm-up of up to ten batches. The LibTorch policy
// here and the torch-free runtime in `mimic bench policy` are timed by this one loop.
template <class Act>
double microseconds_per_batch(const Eigen::MatrixXd& inputs, int batch, double seconds, Act&& act) {
  std::vector<Eigen::MatrixXd> batches;
  for (Eigen::Index r = 0; r + batch <= inputs.rows(); r += batch) batches.push_back(inputs.middleRows(r, batch));
  double sink = 0;
  for (std::size_t i = 0; i < std::min<std::size_t>(batches.size(), 10); ++i) sink += act(batches[i])(0, 0);
  long long calls = 0;
  const Stopwatch clock;
  while (clock.seconds() < seconds)
    for (const Eigen::MatrixXd& b : batches) sink += act(b)(0, 0), ++calls;
  const double elapsed = clock.seconds();
  if (sink == 1234.5678) ++calls;  // keeps the results alive
  return elapsed * 1e6 / static_cast<double>(calls);
}
// The LibTorch policy's mean, so timed.
double libtorch_policy_microseconds(Trainer& trainer, const Eigen::MatrixXd& inputs, int batch, double seconds);

}  // namespace mimic
