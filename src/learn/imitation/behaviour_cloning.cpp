// Behavioural cloning: supervised regression of the policy mean on expert (state, action) pairs,
// the baseline adversarial imitation is compared with (seed 002 section 3.2.1 and A.2).
#include <algorithm>
#include <numeric>

#include "core/error.hpp"
#include "learn/trainer/trainer_impl.hpp"

namespace mimic {

double Trainer::clone_behaviour(const Demonstrations& d, int epochs, double lr, int batch, std::uint64_t seed) {
  Impl& t = *impl_;
  if (t.cfg.policy.net.history != 1) throw Error("behavioural cloning needs a policy that sees one frame (policy.history: 1)");
  if (d.obs.cols() != input_size() || d.action.cols() != action_size())
    throw Error(d.source + ": demonstrations have " + std::to_string(d.obs.cols()) + " observation and " + std::to_string(d.action.cols()) +
                " action values; the policy takes " + std::to_string(input_size()) + " and gives " + std::to_string(action_size()));
  if (epochs < 1 || batch < 1 || !(lr > 0)) throw Error("behavioural cloning: epochs, batch and learning rate must be positive");
  t.obs_norm = RunningNormalizer(input_size(), t.cfg.normalize.clip);
  t.obs_norm.update(d.obs);
  Eigen::MatrixXf x(d.size(), input_size());
  for (int i = 0; i < d.size(); ++i) x.row(i) = t.obs_norm.normalize_one(d.obs.row(i).transpose()).cast<float>().transpose();
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor xr = x, ar = d.action.cast<float>();
  const torch::Tensor inputs = torch::from_blob(const_cast<float*>(xr.data()), {xr.rows(), xr.cols()}, torch::kFloat32).clone();
  const torch::Tensor targets = torch::from_blob(const_cast<float*>(ar.data()), {ar.rows(), ar.cols()}, torch::kFloat32).clone();
  GaussianPolicy& policy = t.learner->policy();
  torch::optim::Adam opt(policy->parameters(), torch::optim::AdamOptions(lr));
  std::mt19937_64 rng(seed);
  std::vector<std::int64_t> order(static_cast<std::size_t>(d.size()));
  std::iota(order.begin(), order.end(), 0);
  double last = 0;
  for (int epoch = 0; epoch < epochs; ++epoch) {
    std::shuffle(order.begin(), order.end(), rng);
    double sum = 0;
    int steps = 0;
    for (std::size_t start = 0; start < order.size(); start += static_cast<std::size_t>(batch)) {
      const std::size_t end = std::min(order.size(), start + static_cast<std::size_t>(batch));
      const torch::Tensor idx = torch::tensor(std::vector<std::int64_t>(order.begin() + static_cast<std::ptrdiff_t>(start), order.begin() + static_cast<std::ptrdiff_t>(end)));
      const torch::Tensor loss = (policy->forward(inputs.index_select(0, idx)).first - targets.index_select(0, idx)).square().mean();
      opt.zero_grad();
      loss.backward();
      opt.step();
      sum += loss.item<double>(), ++steps;
    }
    last = sum / steps;
  }
  return last;
}

}  // namespace mimic
