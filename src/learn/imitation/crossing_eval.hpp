#pragma once
// Crossing a course (seed 000's stairs; any terrain kind but flat): how often a skill gets over
// the environment's terrain. A trial starts from the environment's own start (at the origin,
// facing the course along +x), the skill walking on its own, or, where it takes a heading
// (env.goal: heading), commanded straight along the course for the whole trial. It crosses when
// its root passes `margin` metres beyond the course's last feature (Terrain::course_end) before
// it is down; down is the robustness protocol's rule (DownRule) with the root's height taken
// above the ground under it, so that a character standing on a landing is not lying.
#include <cstdint>
#include <vector>

#include "env/down_rule.hpp"
#include "learn/imitation/imitation_eval.hpp"

namespace mimic {

struct CrossingOptions {
  int trials = 20;
  double seconds = 20.0;  // the longest trial
  double margin = 0.5;    // metres past the last feature that count as across
  std::uint64_t seed = 1;
};

// One trial's bookkeeping, step by step: what measure_crossing keeps for each trial.
class CrossingTrial {
 public:
  CrossingTrial(double finish_x, double standing_height);
  // One control step: the root's x, its height above the ground under it, whether a body that
  // must not touch the ground does, and whether the environment ended the episode as a failure
  // (down at once). Returns true once the trial is decided (crossed or down).
  bool update(double root_x, double height_above_ground, bool fall_contact, bool failed = false);
  bool crossed() const { return crossed_; }
  bool down() const { return down_; }
  double farthest_x() const { return farthest_; }
  int steps() const { return steps_; }

 private:
  double finish_;
  DownRule rule_;
  double farthest_ = 0;
  int steps_ = 0;
  bool crossed_ = false, down_ = false;
};

struct CrossingReport {
  double finish_x = 0, seconds = 0;
  int trials = 0, crossed = 0, falls = 0;  // falls: down before crossing; the rest stopped short
  std::vector<double> progress;            // per trial: the farthest root x over finish_x, at most 1
  std::vector<double> seconds_to_cross;    // per crossing trial
  double success_rate() const { return trials > 0 ? static_cast<double>(crossed) / trials : 0.0; }
};

// Throws Error for flat ground (nothing to cross), options out of range, or episodes that end
// (a time limit) before a trial does.
CrossingReport measure_crossing(CharacterEnv& env, const PolicyFunction& act, int history, const CrossingOptions& options);

}  // namespace mimic
