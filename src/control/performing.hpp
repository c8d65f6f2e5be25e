#pragma once
// Robustness with recovery (seed 004 §6): a skill performs under the projectile test (cubes
// launched at its torso every frame) for a fixed time, in a play session; with recovery skills, a
// character that goes down is handed to the get-up that fits and then back to the skill (the
// session's rules, control/play_session.hpp). The figure is the fraction of the time spent
// performing: up (not down by the session's down rule) with the skill itself in control, not a
// get-up and not waiting for the hand-back. Torch-free.
#include <cstdint>
#include <memory>
#include <vector>

#include "mimic/runtime.hpp"

namespace mimic {

struct PerformingOptions {
  double seconds = 20.0;  // each trial
  int trials = 5;
  // The score at which the skill takes the character back from a get-up that is done
  // (PlayOptions::hand_back_threshold; -1: at once then).
  double hand_back_threshold = -1.0;
  std::uint64_t seed = 1;
};

struct PerformingReport {
  double seconds = 0.0;
  std::vector<double> fractions;  // per trial: the fraction of its control steps performing
  std::vector<int> downs;         // per trial: times the character went down
  std::vector<int> recoveries;    // per trial: times the skill took the character back after a get-up
  // Over the trials (core/statistics.hpp: the population standard deviation; NaN for none).
  double mean() const;
  double std() const;
  double mean_downs() const;
  double mean_recoveries() const;
};

// `skills.front()` performs; the skills after it (none: no recovery) get the character up. The
// skills are loaded by the caller with the projectiles it measures under (Skill::load's env
// settings). Throws mimic::Error for no skills, seconds <= 0 or trials < 1.
PerformingReport measure_performing(const std::vector<std::shared_ptr<const Skill>>& skills, const PerformingOptions& options);

}  // namespace mimic
