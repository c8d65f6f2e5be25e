#pragma once
// PPO's update step (seed 002 section 2.2 and A.2; seed 004 Table 1): clipped surrogate with an
// optional adaptive-beta KL penalty, early stop of policy epochs on large KL, entropy bonus,
// (optionally clipped) value loss, gradient-norm clipping, Adam or SGD with momentum and a
// learning-rate schedule. Policy and value have their own optimizers and epochs; with two or
// more threads the value update runs beside the policy update.
#include <memory>
#include <random>

#include "core/error.hpp"
#include "learn/ppo/divergence.hpp"
#include "learn/networks/networks.hpp"
#include "learn/ppo/ppo_loss.hpp"

namespace mimic {


struct PpoBatch {
  torch::Tensor input;      // [n, in] normalised
  torch::Tensor action;     // [n, a]
  torch::Tensor old_mean, old_log_std;  // [n, a] of the acting policy
  torch::Tensor advantage;  // [n]
  torch::Tensor target;     // [n] TD(lambda) returns
  torch::Tensor old_value;  // [n]
  // Samples an older policy collected (collect.overlap): the policy the update starts from, on
  // the same inputs. Defined, the update is decoupled PPO (ppo_loss.hpp): ratios and the KL are
  // to it, and each sample is weighted by its probability over the acting policy's.
  torch::Tensor prox_mean, prox_log_std;  // [n, a]
};

struct PpoStats {
  double policy_loss = 0, value_loss = 0, kl = 0, entropy = 0, clip_fraction = 0, explained_variance = 0;
  double beta = 0;          // KL penalty weight after this update
  int policy_epochs = 0;    // epochs run (fewer than configured after an early stop)
  double policy_lr = 0, value_lr = 0;
  // The largest gradient norm of a minibatch (before clipping), of each network.
  double policy_grad_norm = 0, value_grad_norm = 0;
};

class PpoLearner {
 public:
  PpoLearner(int input_size, int action_size, const TrainConfig& cfg);

  GaussianPolicy& policy() { return policy_; }
  ValueNet& value() { return value_; }
  torch::optim::Optimizer& policy_optimizer() { return *policy_opt_; }
  torch::optim::Optimizer& value_optimizer() { return *value_opt_; }
  KlController& kl() { return kl_; }

  // Learning rates, and a fixed covariance's log sigma, at `progress` in [0, 1] of the run (the config's schedules).
  void set_progress(double progress);
  // One PPO update on a batch. `iteration` only labels error messages. TrainingDiverged as soon
  // as a loss, the KL, a gradient norm, the log sigma or a weight is non-finite or past its bound
  // (divergence.hpp); Interrupted between minibatches once `interrupted` (set_interrupt) says so.
  // Either leaves the networks part-updated: the caller must not save them.
  PpoStats update(const PpoBatch& batch, std::mt19937_64& rng, bool parallel_value, int iteration);
  // TrainingDiverged naming the first parameter that is not finite or has exploded.
  void check_parameters(int iteration) const;
  void set_interrupt(std::function<bool()> interrupted) { interrupted_ = std::move(interrupted); }

 private:
  void update_policy(const PpoBatch& b, std::mt19937_64& rng, PpoStats& s, int iteration);
  void update_value(const PpoBatch& b, std::mt19937_64& rng, PpoStats& s, int iteration);

  TrainConfig cfg_;
  GaussianPolicy policy_{nullptr};
  ValueNet value_{nullptr};
  std::unique_ptr<torch::optim::Optimizer> policy_opt_, value_opt_;
  KlController kl_;
  std::function<bool()> interrupted_;
};

}  // namespace mimic
