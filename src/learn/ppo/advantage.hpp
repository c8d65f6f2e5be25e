#pragma once
// GAE(lambda) advantages and TD(lambda) value targets (Schulman et al. 2015; seeds 002, 003).
// One environment's steps in time order. An episode that ends by failure is cut off (its next
// value is 0); one truncated by a time limit (or a clip's end) is bootstrapped with the value of
// its last observation, which the collector evaluates and passes as `next_value`.
#include <vector>

namespace mimic {

struct AdvantageStep {
  double reward = 0.0;
  double value = 0.0;       // V(s_t)
  double next_value = 0.0;  // V(s_{t+1}); for an ended episode V(its last observation)
  bool ended = false;       // the episode ended at this step (failure or truncation)
  bool failed = false;      // ... by failure: no bootstrap
};

struct Advantages {
  std::vector<double> advantage;  // GAE(lambda)
  std::vector<double> target;     // TD(lambda) return = advantage + value
};

// delta_t = r_t + gamma * (failed ? 0 : next_value) - value_t;
// A_t = delta_t + gamma * lambda * (ended ? 0 : A_{t+1}). The last step's A_{t+1} is 0: its
// next_value already bootstraps the rest of the trajectory.
Advantages compute_advantages(const std::vector<AdvantageStep>& steps, double gamma, double lambda);

}  // namespace mimic
