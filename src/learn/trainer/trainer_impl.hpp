#pragma once
// The trainer's state, visible to the learn layer, its tests and its benchmark (LibTorch inside).
#include <atomic>
#include <optional>
#include <random>

#include "env/env_factory.hpp"
#include "learn/imitation/adaptive_init.hpp"
#include "learn/ppo/acting_copy.hpp"
#include "learn/ppo/collector.hpp"
#include "learn/ppo/ppo.hpp"
#include "learn/rewards/reward_source.hpp"
#include "learn/trainer/trainer.hpp"

namespace mimic {

struct Trainer::Impl {
  TrainConfig cfg;
  TrainOptions opts;
  EnvFactory factory;
  std::vector<ObservationSlice> layout;  // the environment's observation parts, read once from a probe
  std::unique_ptr<Collector> collector;
  std::unique_ptr<PpoLearner> learner;
  RunningNormalizer obs_norm;
  RunningNormalizer return_norm;            // running std of discounted returns (reward scaling)
  std::vector<double> discounted_return;    // per environment, for reward scaling
  std::vector<std::pair<double, std::unique_ptr<RewardSource>>> rewards;
  // ASI (init: {kind: adaptive}): the distribution the collector's environments start from, and
  // the finished episodes not yet used for a gradient step.
  std::shared_ptr<AdaptiveInit> adaptive_init;
  std::vector<AdaptiveInit::Outcome> init_pending;
  int init_updates = 0;
  std::mt19937_64 noise_rng, shuffle_rng;
  int iteration = 0;
  long long samples = 0;
  double wall_seconds = 0;  // over all segments of a resumed run
  int sources_from_init = 0;  // reward sources whose state came from TrainOptions::init_from
  int context_discriminators_from_init = 0;  // per-context sources loaded from init_discriminators_from
  int contexts_added_by_init = 0;  // > 0: init_from had no behaviour context; its inputs were widened
  std::vector<std::string> parts_added_by_init;  // observation parts init_from lacked; its inputs were widened
  int saved_ranks = 1;  // how many ranks trained the checkpoint this run was resumed from
  bool acting_only = false;  // an exported model's state: acts, is not resumed
  std::unique_ptr<RunLog> log;
  // The last completed iteration's checkpoint when it is not on disk yet (with stop_requests).
  std::string unsaved_checkpoint;

  // A rollout with the episodes that ended and the time it took (collected beside learning with
  // collect.overlap: `prefetched` is the next iteration's, `acting` the networks it acts with).
  struct Collected {
    Rollout rollout;
    EpisodeStats episodes;
    CollectTimes times;
    bool stale = false;  // collected by the policy before the one that learns from it
  };
  std::optional<Collected> prefetched;
  std::unique_ptr<ActingCopy> acting;

  Impl(TrainConfig c, TrainOptions o);
  IterationMetrics iterate();
  // The rollout of iteration `for_iteration` (1-based: what the step hook reports).
  Collected collect(int for_iteration, GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm);
  std::atomic<int> collecting_iteration{0};
  // Rewards of the configured sources, weighted and (optionally) scaled, into rollout.reward.
  void compute_rewards(Rollout& r);
  PpoBatch make_batch(const Rollout& r) const;
  // A rollout collected beside the previous update (collect.overlap): its values, and the
  // bootstraps that are values of its own samples, from the value network as it is now.
  void refresh_values(Rollout& r);
  // Gathers the collector's finished ASI episodes in environment order; a gradient step per full batch.
  void update_adaptive_init(IterationMetrics& m);
  // RUN/checkpoint.pt, the one it replaces kept as RUN/checkpoint.prev.pt.
  void save_run_checkpoint(const std::string& bytes);
  // Complete episodes on environments of their own (evaluation, recording): training's
  // environments and generators are not touched.
  // `seed` seeds the environments, `rng` draws the action noise.
  Rollout side_episodes(int episodes, std::uint64_t seed, std::mt19937_64& rng, bool deterministic, EpisodeStats& stats);
  // Every step of `episodes` such episodes as demonstrations (a student's own states, for
  // distillation), sampled actions unless `deterministic`; `seed` seeds starts and noise.
  Demonstrations record(int episodes, bool deterministic, std::uint64_t seed, EpisodeStats& stats);
};

// Over several ranks (ranks.hpp, rank_state.cpp): the seed of this rank's own generators
// (environments, action noise, minibatches, the discriminators' draws), the config's on rank 0 so
// that one process is unchanged (the networks start from the config's seed on every rank: the
// copies begin identical); this rank's generators as text and back; and fresh ones for the
// iteration a checkpoint holds, where it does not hold this rank's (saved over another count).
std::uint64_t rank_seed(std::uint64_t seed);
std::string generator_state(const Trainer::Impl& t);
void set_generator_state(Trainer::Impl& t, const std::string& text);
void reseed_generators(Trainer::Impl& t);

// The learn layer's way in to a trainer's state (the Trainer has no public one).
struct TrainerAccess {
  static Trainer::Impl& of(Trainer& t) { return *t.impl_; }
  static const Trainer::Impl& of(const Trainer& t) { return *t.impl_; }
};
inline Trainer::Impl& impl_of(Trainer& t) { return TrainerAccess::of(t); }
inline const Trainer::Impl& impl_of(const Trainer& t) { return TrainerAccess::of(t); }

// Checkpoint file I/O (checkpoint.cpp). Errors name the file and what is wrong. A checkpoint's
// bytes (a LibTorch zip archive whose entries carry CRC-32s); TrainingDiverged, nothing made, when
// a network's weights are not finite or have exploded.
std::string serialize_checkpoint(const Trainer::Impl& t);
void read_checkpoint(Trainer::Impl& t, const std::filesystem::path& path);
// The policy's weights and observation normaliser alone (a few MB, atomic): what averaging needs.
// Refused where a checkpoint is read.
void write_policy_snapshot(const Trainer::Impl& t, const std::filesystem::path& path);
// A fresh run's start from another run's (or an exported model's) checkpoint: policy, value,
// normalisers and the state of every reward source saved at the same place in the config's list
// (discriminators); optimisers, counters and generators stay fresh. With a fixed covariance the
// config's log_std replaces the saved one. Returns how many reward sources were loaded.
int read_weights(Trainer::Impl& t, const std::filesystem::path& path);
// Part k of every per-context adversarial source from checkpoints[k]: the single discriminator
// saved there at the same place in the list (a run on context k's behaviour alone). Error when
// the config has no such source, the counts differ, or a checkpoint holds another kind. Returns
// how many sources were loaded.
int read_context_discriminators(Trainer::Impl& t, const std::vector<std::filesystem::path>& checkpoints);
// The policy's weights become the mean of its own and those saved in `checkpoints` (the same
// run's checkpoints or policy snapshots); value, normalisers and discriminators stay this trainer's.
// Returns the largest distance, in this normaliser's standard deviations, from its observation
// mean to a checkpoint's: how far the averaged weights' inputs were normalised differently.
double average_policy(Trainer::Impl& t, const std::vector<std::filesystem::path>& checkpoints);
// The policy, observation normaliser and counters saved in `path` (a checkpoint or snapshot of
// this config) replace this trainer's; value and discriminators stay. Unchanged on error.
void read_policy(Trainer::Impl& t, const std::filesystem::path& path);
// Whether the file is an acting-only export (mimic export), read without building a trainer.
bool is_exported_checkpoint(const std::filesystem::path& path);
// The iteration a checkpoint holds, its integrity checked; Error naming the file otherwise.
int checkpoint_iteration(const std::filesystem::path& path);

}  // namespace mimic
