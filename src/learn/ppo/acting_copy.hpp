#pragma once
// A frozen copy of the policy, the value network and the observation normaliser that a rollout is
// collected with while the learner updates the originals (collect.overlap: the workers collect
// iteration k+1 with iteration k's policy while the learner learns from iteration k's samples).
#include "learn/networks/networks.hpp"
#include "learn/networks/normalizer.hpp"
#include "learn/trainer/train_config.hpp"

namespace mimic {

class ActingCopy {
 public:
  // Networks shaped as the learner's; the global LibTorch generator is left as it was (building
  // them draws initial weights that are overwritten at once).
  ActingCopy(int input_size, int action_size, const TrainConfig& cfg);

  // Takes the current weights (parameters and buffers) and normaliser statistics.
  void take(GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm);

  GaussianPolicy& policy() { return policy_; }
  ValueNet& value() { return value_; }
  const RunningNormalizer& norm() const { return norm_; }

 private:
  GaussianPolicy policy_{nullptr};
  ValueNet value_{nullptr};
  RunningNormalizer norm_;
};

}  // namespace mimic
