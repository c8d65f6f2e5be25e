#pragma once
// Behaviour switches (seed 000's context): does one policy change behaviour when its context
// changes, and keep its feet while it does? A trial starts the environment (its own reset), holds
// context `from` for `hold_steps` control steps, then context `to` for as many. Per trial: whether
// the character fell (the environment's failure rule) before or after the switch, and its
// horizontal speed in each hold, measured on the root body (MuJoCo body 1) over the hold's second
// half, when it has settled into the behaviour. Torch-free: the policy is any function of the
// stacked observations.
#include <functional>
#include <vector>

#include "env/context_env.hpp"

namespace mimic {

struct SwitchReport {
  int from = 0, to = 0, hold_steps = 0, trials = 0;
  double hold_seconds = 0;
  int fell_before = 0;  // trials that fell while holding `from` (they end there)
  int fell_after = 0;   // trials that fell after the switch to `to`
  std::vector<double> speed_before;  // per trial that was up at the switch (m/s)
  std::vector<double> speed_after;   // per trial that was up at the end (m/s)
};

// Runs the trials with `act` on inputs of `history` stacked frames (mean actions are the caller's
// choice). Leaves the env's context released. Throws Error for contexts outside the env's range,
// from == to, hold_steps < 2, trials < 1, an env without physics, or an episode that ends other
// than by a fall before the trial does (a time limit or clip end shorter than two holds).
using StackedPolicy = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
SwitchReport measure_switch(ContextEnv& env, const StackedPolicy& act, int history, int from, int to, int trials, int hold_steps,
                            std::uint64_t seed = 1);

}  // namespace mimic
