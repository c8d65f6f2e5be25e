#pragma once
// Seed 004 section 6.5's transition test: for every ordered pair of skills of one character, the
// character performs the first, a switch to the second is requested at a random moment, and the
// switch succeeds when the second takes over and keeps the character up (not lying: the root
// below half its height at the request for 10 frames) and performing (its own switch score above
// a level) for a while after. Per switch rule and threshold: success rate and
// the mean wait from request to take-over. Torch-free.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mimic/runtime.hpp"

namespace mimic {

struct TransitionOptions {
  int trials = 20;                                // per pair, rule and threshold
  // Seconds into the first skill's episode; for a skill whose episode is shorter (a one-shot clip),
  // within 40 % to 80 % of it.
  double earliest_request = 1.0, latest_request = 3.0;
  double hold_seconds = 2.0;                      // after the take-over, the second must stay up this long
  double performing_score = 0.0;                  // and its score over the hold's last second average above this
  // tau of the score rule: seed 004's 0 to 1, and below 0, where skills trained apart score each
  // other's motion.
  std::vector<double> thresholds = {-0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0};
  bool score_rule = true;                         // seed 004's rule at each threshold
  bool immediate_baseline = true;                 // also switch at once (the rule without a check)
  // Seed 004's other baselines, at the same thresholds: by the target's value (its value network's
  // estimate at least tau times its mean estimate over its own first episode), and by pose
  // matching (SwitchRule::By::Matching: readiness at least tau).
  bool value_baseline = true, matching_baseline = true;
  double time_limit_seconds = 2.0;                // a request not granted by then fails the trial
  std::uint64_t seed = 1;
};

struct TransitionCell {
  std::string from, to, rule;  // rule: "score", "value", "matching" or "immediately"
  double threshold = 0.0;      // tau (the value rule's is over the target's mean value: value_threshold is what it compared)
  double value_threshold = 0.0;
  int trials = 0;
  int switched = 0;            // requests granted within the time limit
  int succeeded = 0;           // granted, then up and performing through the hold
  int fell = 0;                // granted, then down during the hold
  double mean_wait = 0.0;      // seconds from request to take-over, over the granted ones
  double success_rate() const { return trials ? static_cast<double>(succeeded) / trials : 0.0; }
};

// Every ordered pair of `skills` (two or more, one character). `progress` is called after each
// cell. Trials whose first skill falls before the request are drawn again (up to 5 times each).
std::vector<TransitionCell> measure_transitions(const std::vector<std::shared_ptr<const Skill>>& skills, const TransitionOptions& o,
                                                const std::function<void(const TransitionCell&)>& progress = {});

}  // namespace mimic
