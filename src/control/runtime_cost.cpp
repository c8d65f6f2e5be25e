#include "control/runtime_cost.hpp"

#include <algorithm>

#include "control/skill_impl.hpp"
#include "core/stopwatch.hpp"

namespace mimic {

namespace {

// Median microseconds of `passes` calls of `f` after passes / 10 unmeasured ones.
template <class F>
double median_microseconds(int passes, F&& f) {
  for (int i = 0; i < std::max(1, passes / 10); ++i) f();
  std::vector<double> us(static_cast<std::size_t>(std::max(1, passes)));
  for (double& t : us) {
    const Stopwatch w;
    f();
    t = w.seconds() * 1e6;
  }
  auto mid = us.begin() + static_cast<std::ptrdiff_t>(us.size() / 2);
  std::nth_element(us.begin(), mid, us.end());
  return *mid;
}

}  // namespace

RuntimeCost policy_cost(const Skill& skill, int passes) {
  const Eigen::VectorXd input = Eigen::VectorXd::Constant(skill.input_size(), 0.1);
  RuntimeCost c{"policy", skill.policy_parameters(), 0};
  c.microseconds = median_microseconds(passes, [&] { (void)skill.act(input); });
  return c;
}

std::vector<RuntimeCost> discriminator_costs(const Skill& skill, int passes) {
  std::vector<RuntimeCost> out;
  const Eigen::MatrixXd obs = Eigen::MatrixXd::Constant(1, skill.frame_size(), 0.1), actions = Eigen::MatrixXd::Zero(1, skill.action_size());
  std::vector<std::string> timed;
  for (const SkillDiscriminator& d : skill.impl().discriminators) {
    if (std::find(timed.begin(), timed.end(), d.source) != timed.end()) continue;
    timed.push_back(d.source);
    const int context = d.contexts > 0 ? 0 : -1;
    RuntimeCost c{d.source, d.net.parameters(), 0};
    c.microseconds = median_microseconds(passes, [&] { (void)d.rewards(obs, obs, actions, context); });
    out.push_back(c);
  }
  return out;
}

}  // namespace mimic
