#include "learn/ppo/advantage.hpp"

#include "core/error.hpp"

namespace mimic {

Advantages compute_advantages(const std::vector<AdvantageStep>& steps, double gamma, double lambda) {
  if (!(gamma >= 0 && gamma <= 1) || !(lambda >= 0 && lambda <= 1)) throw Error("advantages: gamma and lambda must lie in [0, 1]");
  Advantages out;
  out.advantage.resize(steps.size());
  out.target.resize(steps.size());
  double next_advantage = 0.0;
  for (std::size_t i = steps.size(); i-- > 0;) {
    const AdvantageStep& s = steps[i];
    if (s.ended) next_advantage = 0.0;
    const double bootstrap = s.failed ? 0.0 : s.next_value;
    const double delta = s.reward + gamma * bootstrap - s.value;
    const double a = delta + gamma * lambda * next_advantage;
    out.advantage[i] = a;
    out.target[i] = a + s.value;
    next_advantage = a;
  }
  return out;
}

}  // namespace mimic
