#pragma once
// The learn tests' hands on a trainer in memory. The Trainer has no acting API (acting is the
// runtime's, control/); these reach its state through the learn layer's own access
// (trainer_impl.hpp), as its internals do.
#include <random>

#include "core/error.hpp"
#include "core/statistics.hpp"
#include "learn/rewards/adversarial_reward.hpp"
#include "learn/rewards/per_context_reward.hpp"
#include "learn/networks/policy_timing.hpp"
#include "learn/trainer/trainer_impl.hpp"

namespace mimic::test {

// The policy's mean action for one raw input, with LibTorch.
inline Eigen::VectorXd act(Trainer& t, const Eigen::VectorXd& input) {
  return libtorch_policy_actions(t, input.transpose()).row(0).transpose();
}

// Returns, lengths and failures of `episodes` episodes on environments of their own (mean actions
// unless `stochastic`), as `mimic eval` runs them.
inline EpisodeStats run_episodes(Trainer& t, int episodes, std::uint64_t seed = 12345, bool stochastic = false) {
  EpisodeStats stats;
  std::mt19937_64 rng(seed);
  (void)impl_of(t).side_episodes(episodes, seed, rng, !stochastic, stats);
  return stats;
}
inline double evaluate(Trainer& t, int episodes, std::uint64_t seed = 12345) { return mean_of(run_episodes(t, episodes, seed).returns); }

// Demonstrations from the policy's episodes, as `mimic record` keeps them.
inline Demonstrations record(Trainer& t, int episodes, int every, bool deterministic, std::uint64_t seed, std::vector<double>* returns = nullptr) {
  EpisodeStats stats;
  std::mt19937_64 rng(seed);
  const Rollout r = impl_of(t).side_episodes(episodes, seed, rng, deterministic, stats);
  if (returns) *returns = stats.returns;
  return demonstrations_of(r, t.observation_layout(), every, rng);
}

// The first adversarial reward source's rewards for `d` under behaviour context `context`.
inline std::vector<double> discriminator_scores(Trainer& t, const Demonstrations& d, int context) {
  for (auto& [weight, source] : impl_of(t).rewards) {
    if (auto* adversarial = dynamic_cast<AdversarialRewardSource*>(source.get())) return adversarial->score(d, context);
    if (auto* separate = dynamic_cast<PerContextRewardSource*>(source.get())) return separate->score(d, context);
  }
  throw Error("the trainer has no adversarial reward source");
}

}  // namespace mimic::test
