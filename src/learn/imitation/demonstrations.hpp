#pragma once
// Expert demonstrations for adversarial imitation: (observation, action, next observation)
// samples tagged with their episode, as recorded from a trained policy (`mimic record`) or made
// by a program. Stored as CSV: an optional first line `# layout: name offset size; ...` naming
// the parts of an observation (so a discriminator can pick the same part from an expert of a
// different body), a header `episode,obs_0..,action_0..,next_obs_0..`, a row per sample.
// Torch-free.
#include <Eigen/Core>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "env/env.hpp"
#include "learn/ppo/rollout.hpp"

namespace mimic {

struct Demonstrations {
  Eigen::MatrixXd obs, action, next_obs;  // one row per sample
  std::vector<int> episode;
  std::vector<ObservationSlice> layout;  // empty when the file named none
  std::string source;  // file it came from, for messages

  int size() const { return static_cast<int>(obs.rows()); }
  int episodes() const;  // distinct episode tags
  // The samples of the first `n` episodes (in order of first appearance); all if fewer.
  Demonstrations first_episodes(int n) const;
  // `more`'s samples after these, its episodes renumbered after this set's (several clips in one
  // file). Error when the column counts or the layouts differ.
  void append(const Demonstrations& more);
};

// Demonstrations from whole episodes (a collector's or the runtime's, run_episodes): every
// `every`-th step of each episode from an offset drawn from `rng` per episode (seed 002:
// sub-sampled every 20 steps), environment by environment; the observation without its history.
Demonstrations demonstrations_of(const Rollout& episodes, std::vector<ObservationSlice> layout, int every, std::mt19937_64& rng);

// Errors (ParseError) name the file, the line and the problem: a missing column group, sizes
// that disagree, a cell that is not a finite number, no samples, a layout outside the observation.
Demonstrations read_demonstrations(const std::filesystem::path& path);
// The same from a file's text; `where` names it in errors.
Demonstrations parse_demonstrations(std::string text, const std::string& where);
void write_demonstrations(const std::filesystem::path& path, const Demonstrations& d);  // atomic

}  // namespace mimic
