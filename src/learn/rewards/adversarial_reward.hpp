#pragma once
// Adversarial imitation as a reward source: a discriminator learns to tell expert transitions
// from the policy's, and the policy is rewarded for being taken for the expert. `gail` is seed
// 000/002's single binary classifier (reward -log(1 - D), clipped); `iccgan` is seed 004's
// ensemble of hinge-loss heads with a gradient penalty (reward: mean of clipped heads). The
// discriminator sees a chosen subset of the observation (seed 000: egocentric features only),
// of the next state alone, of both states, or of the state and the action.
#include <Eigen/Core>
#include <memory>

#include "core/config_section.hpp"
#include "learn/imitation/demonstrations.hpp"
#include "learn/rewards/discriminator.hpp"
#include "learn/rewards/reward_source.hpp"

namespace mimic {

using FeatureRows = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Which numbers of a transition the discriminator sees. With behaviour contexts (seed 000), each
// state's chosen entries are followed by its one-hot context: read from the observation on the
// policy's side, fixed per demonstrations file on the expert's.
struct TransitionFeatures {
  std::string transition = "s";  // s: next state s'; ss: (s, s'); sa: (s, a)
  std::vector<int> columns;      // chosen entries of an observation frame
  int action_size = 0;
  int contexts = 0;              // > 0: a one-hot context follows each state's entries
  int context_offset = -1;       // where the observation holds it (the policy's side), or
  int fixed_context = -1;        // the context of every sample (an expert file's side)

  int state_width() const { return static_cast<int>(columns.size()) + contexts; }
  int width() const;
  FeatureRows of(const Rollout& r) const;
  FeatureRows of(const Demonstrations& d) const;
};

// Columns of the named observation slices, in the order named; all columns when `names` is empty.
// Error naming the config and the known slices for an unknown name.
std::vector<int> slice_columns(const std::vector<ObservationSlice>& layout, int frame_size, const std::vector<std::string>& names,
                               const std::string& where);

class AdversarialRewardSource : public RewardSource {
 public:
  // `expert` holds the expert's features by the same rule (TransitionFeatures::of on the
  // demonstrations, whose columns differ when the expert had another body).
  AdversarialRewardSource(std::string name, TransitionFeatures features, const FeatureRows& expert, const DiscriminatorConfig& cfg,
                          std::uint64_t seed);
  std::string name() const override { return name_; }
  std::vector<double> rewards(const Rollout& rollout) override;
  std::vector<std::pair<std::string, double>> update(const Rollout& rollout) override;
  void drop_training_state() override { disc_.drop_training_state(); }
  void set_interrupt(std::function<bool()> interrupted) override { disc_.set_interrupt(std::move(interrupted)); }
  void check_weights() const override { disc_.check_weights(); }
  void save(torch::serialize::OutputArchive& a) const override;
  void load(torch::serialize::InputArchive& a) override;
  void load_widened(torch::serialize::InputArchive& a, int added_contexts) override;
  // The reward this source gives each transition of `d` (observations without a context), as if
  // a policy had made it under behaviour context `context` (-1 for a source without contexts):
  // how expert-like the discriminator finds a motion, and whether it tells the contexts apart.
  // Error naming the file where `d` does not fit the features, or for a context out of range.
  std::vector<double> score(const Demonstrations& d, int context);
  Discriminator& discriminator() { return disc_; }
  const TransitionFeatures& features() const { return features_; }

 private:
  std::string name_;
  TransitionFeatures features_;
  Discriminator disc_;
  double last_reward_ = 0;
};

// `kind` is gail or iccgan (their defaults differ); reads the entry's remaining keys from `s`.
std::unique_ptr<RewardSource> make_adversarial_reward_source(const std::string& kind, ConfigSection& s, const YamlReader& reader,
                                                             const RewardSourceContext& context);

}  // namespace mimic
