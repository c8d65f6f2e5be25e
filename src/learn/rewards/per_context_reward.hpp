#pragma once
// One discriminator per behaviour context (adversarial rewards with `per_context: true`): part k
// learns from context k's expert file and from the policy's samples taken under context k alone,
// and rewards those samples. A single discriminator with the one-hot among its inputs may learn
// to ignore it (on the walk/run humanoid it moved its reward by 0.03–0.07 of 2 between contexts,
// `mimic score`), and then a policy that ignores its context loses nothing; a part never sees
// another context's expert motion as real, so acting out the wrong behaviour scores as fake.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "learn/rewards/adversarial_reward.hpp"

namespace mimic {

class PerContextRewardSource : public RewardSource {
 public:
  // `parts[k]` sees observations without the context; `context_offset` is where the policy's
  // observation holds its one-hot (of parts.size() values). Error with fewer than two parts.
  PerContextRewardSource(std::string name, int context_offset, std::vector<std::unique_ptr<AdversarialRewardSource>> parts);
  std::string name() const override { return name_; }
  std::vector<double> rewards(const Rollout& rollout) override;
  // Each part's metrics with the suffix _c<k> (its samples only).
  std::vector<std::pair<std::string, double>> update(const Rollout& rollout) override;
  void drop_training_state() override;
  void set_interrupt(std::function<bool()> interrupted) override {
    for (auto& p : parts_) p->set_interrupt(interrupted);
  }
  void check_weights() const override {
    for (const auto& p : parts_) p->check_weights();
  }
  void save(torch::serialize::OutputArchive& a) const override;
  void load(torch::serialize::InputArchive& a) override;
  // From a run without contexts: every part starts as its single discriminator (whose inputs
  // are the parts' own: no widening).
  void load_widened(torch::serialize::InputArchive& a, int added_contexts) override;
  // Part `context`'s rewards for `d` (AdversarialRewardSource::score); Error outside the contexts.
  std::vector<double> score(const Demonstrations& d, int context);
  int contexts() const { return static_cast<int>(parts_.size()); }
  AdversarialRewardSource& part(int k) { return *parts_.at(static_cast<std::size_t>(k)); }

 private:
  // The samples of each context: the one-hot the policy acted under (the state's, not the next).
  std::vector<std::vector<int>> rows_by_context(const Rollout& r) const;
  std::string name_;
  int context_offset_;
  std::vector<std::unique_ptr<AdversarialRewardSource>> parts_;
  std::vector<std::vector<std::string>> metric_names_;  // each part's, for an iteration without its samples
};

// The rollout's samples `rows`, in that order, with what a reward source reads of them (inputs,
// next observations, actions, environment rewards); advantages and episodes are not kept.
Rollout rollout_rows(const Rollout& r, const std::vector<int>& rows);

}  // namespace mimic
