#include "learn/runtime_cost.hpp"

#include <algorithm>

#include "core/stopwatch.hpp"
#include "learn/adversarial_reward.hpp"
#include "learn/per_context_reward.hpp"
#include "learn/trainer.hpp"
#include "learn/trainer_impl.hpp"

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

RuntimeCost policy_cost(const Trainer& trainer, int passes) {
  const Eigen::VectorXd input = Eigen::VectorXd::Constant(trainer.input_size(), 0.1);
  RuntimeCost c{"policy", trainer.policy_parameters(), 0};
  c.microseconds = median_microseconds(passes, [&] { (void)trainer.act(input); });
  return c;
}

std::vector<RuntimeCost> discriminator_costs(Trainer& trainer, int passes) {
  std::vector<RuntimeCost> out;
  for (auto& entry : trainer.impl().rewards) {
    auto* adversarial = dynamic_cast<AdversarialRewardSource*>(entry.second.get());
    // One discriminator per context: a step is scored by its context's alone.
    if (auto* separate = dynamic_cast<PerContextRewardSource*>(entry.second.get())) adversarial = &separate->part(0);
    if (!adversarial) continue;
    Discriminator& d = adversarial->discriminator();
    RuntimeCost c{adversarial->name(), 0, 0};
    for (const auto& p : d.net()->parameters()) c.parameters += p.numel();
    const torch::Tensor x = d.expert().slice(0, 0, 1).clone();  // one real transition
    c.microseconds = median_microseconds(passes, [&] { (void)d.reward(x); });
    out.push_back(c);
  }
  return out;
}

}  // namespace mimic
