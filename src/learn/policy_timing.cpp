#include "learn/policy_timing.hpp"

#include "core/stopwatch.hpp"
#include "learn/trainer_impl.hpp"

namespace mimic {

namespace {

using RowMajorFloats = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

Eigen::MatrixXd mean_actions(Trainer::Impl& t, const Eigen::MatrixXd& inputs) {
  torch::NoGradGuard no_grad;
  const RowMajorFloats x = t.obs_norm.normalize(inputs).cast<float>();
  const torch::Tensor mean =
      t.learner->policy()->forward(torch::from_blob(const_cast<float*>(x.data()), {x.rows(), x.cols()}, torch::kFloat32)).first.contiguous();
  return Eigen::Map<const RowMajorFloats>(mean.data_ptr<float>(), mean.size(0), mean.size(1)).cast<double>();
}

}  // namespace

Eigen::MatrixXd libtorch_policy_actions(Trainer& trainer, const Eigen::MatrixXd& inputs) { return mean_actions(trainer.impl(), inputs); }

double libtorch_policy_microseconds(Trainer& trainer, const Eigen::MatrixXd& inputs, int batch, double seconds) {
  std::vector<Eigen::MatrixXd> batches;
  for (Eigen::Index r = 0; r + batch <= inputs.rows(); r += batch) batches.push_back(inputs.middleRows(r, batch));
  double sink = 0;
  for (std::size_t i = 0; i < std::min<std::size_t>(batches.size(), 10); ++i) sink += mean_actions(trainer.impl(), batches[i])(0, 0);
  long long calls = 0;
  const Stopwatch clock;
  while (clock.seconds() < seconds)
    for (const Eigen::MatrixXd& b : batches) sink += mean_actions(trainer.impl(), b)(0, 0), ++calls;
  const double elapsed = clock.seconds();
  if (sink == 1234.5678) calls += 0;  // keeps the results alive
  return elapsed * 1e6 / static_cast<double>(calls);
}

}  // namespace mimic
