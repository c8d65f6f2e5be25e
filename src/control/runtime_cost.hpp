#pragma once
// Seed 004 Table 4's runtime cost of a trained skill, on the runtime: parameter count, model size
// and the time of one forward pass at batch 1, for the policy and for each discriminator (ensemble)
// it learnt against. Timed as the median of `passes` calls after a warm-up, on the calling thread.
#include <string>
#include <vector>

#include "mimic/runtime.hpp"

namespace mimic {

struct RuntimeCost {
  std::string name;          // "policy", or the reward source's name (gail, iccgan)
  long long parameters = 0;  // trainable values
  double microseconds = 0;   // median time of one pass at batch 1
  double megabytes() const { return static_cast<double>(parameters) * 4.0 / 1e6; }  // as float32
};

// The policy's mean action for one raw input (normalisation included).
RuntimeCost policy_cost(const Skill& skill, int passes = 2000);
// One reward of one transition (features, standardisation and the reward's rule included), per
// discriminator source (a per-context source by its first context's: a step is scored by one);
// empty for a skill without discriminators.
std::vector<RuntimeCost> discriminator_costs(const Skill& skill, int passes = 2000);

}  // namespace mimic
