#pragma once
// Seed 004 Table 4's runtime cost of a trained controller: parameter count, model size and the
// time of one forward pass at batch 1, for the policy and for each discriminator (ensemble) a
// run trained with. Timed as the median of `passes` calls after a warm-up, on the calling thread.
#include <string>
#include <vector>

namespace mimic {

class Trainer;

struct RuntimeCost {
  std::string name;          // "policy", or the reward source's name (gail, iccgan)
  long long parameters = 0;  // trainable values
  double microseconds = 0;   // median time of one pass at batch 1
  double megabytes() const { return static_cast<double>(parameters) * 4.0 / 1e6; }  // as float32
};

// The policy's mean action for one raw input (normalisation included).
RuntimeCost policy_cost(const Trainer& trainer, int passes = 2000);
// One reward from one transition's features (standardisation included), per adversarial reward
// source; empty when the run has none (or was loaded without its reward sources).
std::vector<RuntimeCost> discriminator_costs(Trainer& trainer, int passes = 2000);

}  // namespace mimic
