#pragma once
// Whole episodes of a skill in its own environment, run as training's collector runs them
// (learn/ppo/collector.hpp, episodes mode): `slots` environments side by side, each with its own
// generator drawn from (seed, "mimic"), inference batched over the environments still running,
// exploration noise drawn in environment order. So the same seed gives the episodes `mimic train`
// would have evaluated, on the torch-free networks: what `mimic eval` reports and `mimic record`
// keeps. Torch-free.
#include <cstdint>
#include <random>

#include "learn/ppo/rollout.hpp"
#include "mimic/runtime.hpp"

namespace mimic {

struct EpisodeOptions {
  int episodes = 20;
  int slots = 1;    // environments side by side (training's collect.envs; at most `episodes` are used)
  int threads = 1;  // threads stepping them (the results do not depend on it)
  std::uint64_t seed = 12345;  // the environments' generators (their starts)
  bool deterministic = true;   // the policy's mean; else sampled with its sigma, noise from the caller's generator
  // A baseline: this action in place of the policy's mean at every step (empty: the policy's),
  // e.g. a navigation controller's 0, "straight on". Its size must be the skill's action size.
  Eigen::VectorXd fixed_action;
};

// Runs o.episodes complete episodes. Returns the steps in the collector's layout (raw inputs, next
// observations, actions and the means they were drawn around, rewards, endings, each slot's steps
// in time order); policy values are not filled. `stats` receives returns, lengths and failures in
// the order the episodes ended. Error naming the skill for a non-finite or wrongly sized
// observation or reward.
Rollout run_episodes(const Skill& skill, const EpisodeOptions& o, std::mt19937_64& noise_rng, EpisodeStats& stats);

}  // namespace mimic
