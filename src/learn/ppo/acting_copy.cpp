#include "learn/ppo/acting_copy.hpp"

#include <ATen/CPUGeneratorImpl.h>

#include "core/error.hpp"

namespace mimic {

namespace {

void copy_module(torch::nn::Module& from, torch::nn::Module& to) {
  torch::NoGradGuard no_grad;
  const auto source = from.named_parameters(), target = to.named_parameters();
  const auto source_buffers = from.named_buffers(), target_buffers = to.named_buffers();
  if (source.size() != target.size() || source_buffers.size() != target_buffers.size())
    throw Error("acting copy: the networks' shapes differ from the learner's");
  for (std::size_t i = 0; i < source.size(); ++i) target[i].value().copy_(source[i].value());
  for (std::size_t i = 0; i < source_buffers.size(); ++i) target_buffers[i].value().copy_(source_buffers[i].value());
}

}  // namespace

ActingCopy::ActingCopy(int input_size, int action_size, const TrainConfig& cfg) {
  at::Generator generator = at::detail::getDefaultCPUGenerator();
  const at::Tensor state = generator.get_state();
  policy_ = GaussianPolicy(input_size, action_size, cfg.policy);
  value_ = ValueNet(input_size, cfg.value);
  generator.set_state(state);
}

void ActingCopy::take(GaussianPolicy& policy, ValueNet& value, const RunningNormalizer& norm) {
  copy_module(*policy, *policy_);
  copy_module(*value, *value_);
  norm_ = norm;
}

}  // namespace mimic
