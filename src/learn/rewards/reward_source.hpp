#pragma once
// Where the learner's reward comes from. The trainer asks every configured source for a reward
// per sample of a rollout and sums them with their weights; sources that learn (discriminators)
// update after the policy and save their state with the checkpoint. Tracking, GAIL and ICCGAN
// rewards plug in here without touching the trainer.
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "env/env.hpp"
#include "learn/ppo/rollout.hpp"
#include "learn/trainer/train_config.hpp"

namespace torch::serialize {
class OutputArchive;
class InputArchive;
}  // namespace torch::serialize

namespace mimic {

class RewardSource {
 public:
  virtual ~RewardSource() = default;
  virtual std::string name() const = 0;
  // One reward per sample of the rollout.
  virtual std::vector<double> rewards(const Rollout& rollout) = 0;
  // After the policy update; returns named metrics for the log.
  virtual std::vector<std::pair<std::string, double>> update(const Rollout&) { return {}; }
  // Polled between the source's own learning steps in update(): once it returns true, update()
  // throws Interrupted (the source is then part-updated: not to be saved).
  virtual void set_interrupt(std::function<bool()>) {}
  // TrainingDiverged naming the first weight of the source's networks that is NaN, infinite or
  // exploded (divergence.hpp); update() checks its losses and weights itself.
  virtual void check_weights() const {}
  // For an exported model: forget what only further training needs (optimiser moments, replay).
  virtual void drop_training_state() {}
  virtual void save(torch::serialize::OutputArchive&) const {}
  virtual void load(torch::serialize::InputArchive&) {}
  // load() of state saved before the observation gained a one-hot of `added_contexts` after each
  // state (--init-from a single-behaviour run into a context run); an error where it cannot.
  virtual void load_widened(torch::serialize::InputArchive& a, int added_contexts);
};

// The environment's own task reward.
class EnvRewardSource : public RewardSource {
 public:
  std::string name() const override { return "env"; }
  std::vector<double> rewards(const Rollout& rollout) override { return rollout.env_reward; }
};

// What a source may need to know about the run it serves.
struct RewardSourceContext {
  std::string config_source;  // the config's path or label: messages, and files named beside it
  int frame_size = 0, action_size = 0;
  std::vector<ObservationSlice> layout;  // the environment's named observation parts
  std::uint64_t seed = 1;
};

// A source by its config name (env, gail, iccgan); Error naming the source and the known ones otherwise.
std::unique_ptr<RewardSource> make_reward_source(const RewardSourceConfig& cfg, const RewardSourceContext& context);

}  // namespace mimic
