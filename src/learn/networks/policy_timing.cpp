#include "learn/networks/policy_timing.hpp"

#include "learn/trainer/trainer_impl.hpp"

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

Eigen::MatrixXd libtorch_policy_actions(Trainer& trainer, const Eigen::MatrixXd& inputs) { return mean_actions(impl_of(trainer), inputs); }

double libtorch_policy_microseconds(Trainer& trainer, const Eigen::MatrixXd& inputs, int batch, double seconds) {
  return microseconds_per_batch(inputs, batch, seconds, [&](const Eigen::MatrixXd& b) { return mean_actions(impl_of(trainer), b); });
}

}  // namespace mimic
