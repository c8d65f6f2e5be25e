#pragma once
// `mimic bench train`: end-to-end PPO throughput (simulation + inference + learning) on the
// humanoid with seed 004's Table 1 sizes (policy and value 1024-512, 5 epochs, minibatch 256,
// buffer 4096), or of any training config (imitation: discriminator updates included), beside the
// simulation-only rate measured in the same run with the same threads.
#include <functional>
#include <string>
#include <vector>

namespace mimic {

struct TrainBenchOptions {
  std::vector<int> threads{1, 2};
  int iterations = 3;   // timed, after one warm-up iteration
  int samples = 4096;
  int envs = 16;
  bool overlap = false;  // each thread count also with collect.overlap (learning beside collection)
  // Rounds over all the settings, one after another (so that what else the machine does falls on
  // every setting alike); each figure is the median of its rounds.
  int rounds = 1;
  // A training config (YAML text) to time instead of the built-in one; its collect.threads and
  // iterations are replaced, `samples` and `envs` are its own.
  std::string config_text, config_source;
};

struct TrainBenchResult {
  int ranks = 1;                    // processes of the run (mpirun -np), each with `threads` workers
  int threads = 0;
  bool overlap = false;             // collect.overlap
  double sim_only_steps_per_s = 0;  // random PD targets, resets on falls; all ranks together
  double train_samples_per_s = 0;   // end to end, all ranks together
  double share_simulation = 0, share_inference = 0, share_learning = 0;
  double seconds = 0;               // timed wall time
  double of_sim_only = 0;           // end to end over simulation only (with rounds, the median of each round's)
  double train_min = 0, train_max = 0;  // the rounds' lowest and highest end-to-end rate
  double ratio_min = 0, ratio_max = 0;  // and of_sim_only's
  double sums_per_iteration = 0, bytes_per_iteration = 0;  // over several ranks: what each rank put into sums
};

// Needs the shared data (humanoid3d and its walk); Error naming what is missing otherwise. With
// several rounds, a result per setting: the medians of its rounds.
std::vector<TrainBenchResult> run_train_benchmark(const TrainBenchOptions& opts,
                                                  const std::function<void(const std::string&)>& progress = {});
// One setting's rounds as one result: each figure the median of its rounds (of_sim_only the median
// of each round's ratio), with the rounds' lowest and highest end-to-end rate and ratio.
TrainBenchResult median_of_rounds(const std::vector<TrainBenchResult>& rounds);
// A readable table (Markdown) with the per-core figures, end to end over the simulation-only rate, and
// the scaling from 1 thread.
std::string format_train_benchmark(const TrainBenchOptions& opts, const std::vector<TrainBenchResult>& results);
// The YAML config the benchmark trains with.
std::string train_benchmark_config(const TrainBenchOptions& opts, int threads);

}  // namespace mimic
