#pragma once
// A PPO training run: collect, compute rewards and advantages, update, log, checkpoint.
// Free of LibTorch headers so that the command line and tools include it cheaply.
//
// Run directory: config.yaml (the config as given, with the iteration count the run goes to, which a
// resume rewrites to its own so that the next plain resume keeps it), checkpoint.pt (written
// atomically and durably every `checkpoint_every` iterations and at exit; the one it replaced is
// kept as checkpoint.prev.pt), metrics.csv, tensorboard/events.*. Checkpoints carry CRC-32s that
// every read verifies; a diverged state is never saved (docs/reliability.md).
// Reproducibility: the same config and seed give the same metrics, whatever the thread count.
// Every checkpoint also restarts the episodes in progress, so that a run resumed from a periodic
// checkpoint continues exactly as the uninterrupted run did (one written between those, at an
// urgent stop or an --iterations that is not a multiple, restarts them where that run did not).
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "env/env_factory.hpp"
#include "learn/imitation/demonstrations.hpp"
#include "learn/ppo/rollout.hpp"
#include "learn/trainer/run_log.hpp"
#include "learn/trainer/train_config.hpp"

namespace mimic {

struct TrainOptions {
  std::filesystem::path run_dir;       // empty: no files at all (tests, benchmarks)
  bool resume = false;                 // continue from run_dir/checkpoint.pt
  // A new run started from another's weights (its checkpoint.pt, or an exported model's): policy,
  // value, normalisers and discriminators; fresh optimisers and counters (fine-tuning under a
  // changed config). Not with resume.
  std::filesystem::path init_from;
  // A new run's discriminators per behaviour context (rewards with per_context), each from its
  // own run (or model) on that behaviour alone, in context order; after init_from, so these win.
  // Not with resume.
  std::vector<std::filesystem::path> init_discriminators_from;
  // Stop requests so far (Ctrl-C, SIGTERM), polled between iterations and within them, after every
  // collection step and learning minibatch: from the first, run() stops within one of those and
  // saves the last completed iteration (held in memory between checkpoints for this). A stop
  // between checkpoint_every multiples restarts the episodes in progress there, so the resumed run
  // departs from an unstopped one at that point.
  std::function<int()> stop_requests;
  std::function<void(const IterationMetrics&)> on_iteration;  // progress output
  // The program's own environments instead of the config's `env` section (a game, a test).
  EnvFactory env_factory;
  // Test hook: called after every collection step with (iteration, samples so far in it).
  std::function<void(int, int)> step_hook;
};

// How Trainer::run ended.
struct RunEnd {
  int iteration = 0;         // the last completed iteration: the one the run's checkpoint holds
  bool stopped = false;      // by a stop request, before the config's iteration count
  std::string interrupted;   // not empty: the stop cut the next iteration short (where, in words)
};

class Trainer {
 public:
  Trainer(TrainConfig cfg, TrainOptions opts = {});
  ~Trainer();
  Trainer(const Trainer&) = delete;
  Trainer& operator=(const Trainer&) = delete;

  // Iterates until the config's iteration count or a stop (TrainOptions::stop_requests), then
  // checkpoints the last completed iteration. TrainingDiverged (divergence.hpp) saves nothing: the
  // last checkpoint written stays the run's.
  RunEnd run();
  // One iteration (collect, learn, log; a checkpoint when one is due).
  IterationMetrics iterate();

  int iteration() const;  // iterations completed
  // How many ranks (mpirun) trained the checkpoint this run was resumed from; 1 for a fresh run.
  int saved_ranks() const;
  int reward_sources_initialised() const;  // reward sources loaded from TrainOptions::init_from
  int context_discriminators_initialised() const;  // per-context sources from init_discriminators_from
  // > 0: TrainOptions::init_from was saved without a behaviour context and its networks were
  // widened by this many context inputs (weighing zero: every context starts acting as it did).
  int contexts_added_by_init() const;
  // Observation parts (by name) TrainOptions::init_from was saved without; its networks were
  // widened by them (weighing zero, normalised as their raw values).
  const std::vector<std::string>& parts_added_by_init() const;
  long long samples() const;
  int input_size() const;
  int action_size() const;
  const TrainConfig& config() const;

  void save_checkpoint(const std::filesystem::path& path) const;  // atomic
  void load_checkpoint(const std::filesystem::path& path);
  // An acting-only checkpoint (atomic): networks, normalisers and discriminators, without the
  // optimisers' moments and the discriminators' replay pools — a few MB where a run's checkpoint
  // takes tens. It loads for eval, render, record and embedding; resuming it is refused, since
  // training would go on from fresh moments and an empty pool. This trainer drops them too.
  // Beside it, the torch-free runtime's networks.mimic (write_runtime_networks).
  void export_model(const std::filesystem::path& path);
  // The policy, value network and observation normaliser in the runtime's own format
  // (learn/networks/runtime_export.hpp, docs/runtime.md), atomically.
  void write_runtime_networks(const std::filesystem::path& path) const;
  std::string runtime_networks() const;  // the same file's bytes
  // Averages the policy's weights with those of other checkpoints of the same config (run
  // directories or checkpoint files; stochastic weight averaging over a run's last checkpoints).
  // Returns the largest gap between their observation normalisers' means and this one's, in this
  // one's standard deviations (the averaged weights act on inputs normalised as this trainer's).
  double average_policy_with(const std::vector<std::filesystem::path>& checkpoints);
  // The policy as it was in another checkpoint or snapshot of this run (its weights, observation
  // normaliser, iteration and samples); value and discriminators stay this trainer's.
  void take_policy_from(const std::filesystem::path& checkpoint);
  // RUN/snapshots/<iteration>.pt, written every `snapshot_every` iterations: the policy's
  // weights and normaliser, for averaging. The run's snapshots by iteration, oldest first.
  static std::filesystem::path snapshot_path(const std::filesystem::path& run, int iteration);
  static std::vector<std::pair<int, std::filesystem::path>> policy_snapshots(const std::filesystem::path& run);
  // Behavioural cloning (the baseline of seed 002 A.2): the observation normaliser takes the
  // demonstrations' statistics and the policy mean regresses their actions (mean squared error,
  // Adam). Returns the final training loss. Needs a policy that sees one frame.
  double clone_behaviour(const Demonstrations& d, int epochs, double lr, int batch, std::uint64_t seed);

  // The environment's observation parts (names, offsets and sizes in one frame).
  const std::vector<ObservationSlice>& observation_layout() const;
  // Trainable values of the policy network (its log-std included).
  long long policy_parameters() const;

  // A run from its directory (config.yaml + checkpoint.pt), to export it or convert its networks
  // (acting is the runtime's: control/, include/mimic/runtime.hpp). Its reward sources are left
  // out, so that a run whose discriminator read expert files elsewhere still loads; with
  // `reward_sources` they are built and restored too (their expert files must be found).
  // `settings` override the run's config as `mimic train --set` does (KEY.PATH=VALUE), in memory
  // only. Error naming the run otherwise.
  static std::unique_ptr<Trainer> from_run(const std::filesystem::path& run, bool reward_sources = false,
                                           const std::vector<std::string>& settings = {});

  struct Impl;

 private:
  friend struct TrainerAccess;  // the learn layer's own (trainer_impl.hpp)
  std::unique_ptr<Impl> impl_;
};

}  // namespace mimic
