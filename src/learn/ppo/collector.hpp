#pragma once
// Vectorised experience collection: N environments stepped by a pool of worker threads, the
// policy's inference batched across all of them on the calling thread. Each environment has its
// own random generator, and exploration noise is drawn on the calling thread in environment
// order, so a rollout depends on the seed only, not on thread scheduling.
#include <memory>
#include <random>
#include <vector>

#include "core/worker_pool.hpp"
#include "env/env_factory.hpp"
#include "learn/networks/networks.hpp"
#include "learn/imitation/frame_history.hpp"
#include "learn/networks/normalizer.hpp"
#include "learn/ppo/rollout.hpp"

namespace mimic {

struct CollectTimes {
  double simulation = 0.0;  // seconds stepping environments (wall time of the parallel steps)
  double inference = 0.0;   // seconds in policy/value forward passes and sampling
};

class Collector {
 public:
  // `history`: frames stacked into the policy input (the first frame of an episode fills it).
  Collector(const EnvFactory& factory, int envs, int threads, int history, std::uint64_t seed);
  ~Collector();

  int envs() const { return static_cast<int>(envs_.size()); }
  int frame_size() const { return frame_size_; }
  int input_size() const { return frame_size_ * history_; }
  int action_size() const { return action_size_; }
  Env& env(int i) { return *envs_[static_cast<std::size_t>(i)]; }
  WorkerPool& pool() { return pool_; }

  // Horizon mode: `steps` steps of every environment; episodes continue across calls.
  Rollout collect_steps(int steps, GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm,
                        std::mt19937_64& noise_rng, bool deterministic = false);
  // Episodes mode: every environment restarts; exactly `episodes` complete episodes.
  Rollout collect_episodes(int episodes, GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm,
                           std::mt19937_64& noise_rng, bool deterministic = false);

  // Starts a new episode in every environment.
  void reset_all();
  // Episodes that ended since the last call.
  EpisodeStats take_episode_stats();
  CollectTimes take_times();

  // Random generator states of the environments, for checkpoints.
  std::vector<std::string> rng_states() const;
  void set_rng_states(const std::vector<std::string>& states);
  // Test hook: called with the number of samples collected so far in this call, after each step.
  void set_step_hook(std::function<void(int)> hook) { step_hook_ = std::move(hook); }
  // Polled after every step: once it returns true, the collection throws Interrupted (the
  // environments are then mid-episode; reset_all() before collecting again).
  void set_interrupt(std::function<bool()> interrupted) { interrupted_ = std::move(interrupted); }

 private:
  struct Slot;
  Rollout collect(int steps, int episodes, GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm,
                  std::mt19937_64& noise_rng, bool deterministic);
  void reset_slot(int i);

  std::vector<std::unique_ptr<Env>> envs_;
  std::vector<std::unique_ptr<Slot>> slots_;
  WorkerPool pool_;
  int history_, frame_size_ = 0, action_size_ = 0;
  EpisodeStats stats_;
  CollectTimes times_;
  std::function<void(int)> step_hook_;
  std::function<bool()> interrupted_;
};

}  // namespace mimic
