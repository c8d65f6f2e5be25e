#include "learn/ppo/ppo_loss.hpp"

#include <cmath>
#include <numbers>

namespace mimic {

torch::Tensor gaussian_log_prob(const torch::Tensor& action, const torch::Tensor& mean, const torch::Tensor& log_std) {
  const double log_sqrt_2pi = 0.5 * std::log(2.0 * std::numbers::pi);
  const torch::Tensor z = (action - mean) * torch::exp(-log_std);
  return (-0.5 * z * z - log_std - log_sqrt_2pi).sum(-1);
}

torch::Tensor gaussian_entropy(const torch::Tensor& log_std) {
  const double c = 0.5 * (1.0 + std::log(2.0 * std::numbers::pi));
  return (log_std + c).sum(-1);
}

torch::Tensor gaussian_kl(const torch::Tensor& old_mean, const torch::Tensor& old_log_std, const torch::Tensor& mean,
                          const torch::Tensor& log_std) {
  const torch::Tensor old_var = torch::exp(2.0 * old_log_std), var = torch::exp(2.0 * log_std);
  return (log_std - old_log_std + (old_var + (old_mean - mean).pow(2)) / (2.0 * var) - 0.5).sum(-1);
}

torch::Tensor clipped_surrogate_loss(const torch::Tensor& ratio, const torch::Tensor& advantage, double clip) {
  const torch::Tensor unclipped = ratio * advantage;
  const torch::Tensor clipped = torch::clamp(ratio, 1.0 - clip, 1.0 + clip) * advantage;
  return -torch::min(unclipped, clipped).mean();
}

torch::Tensor decoupled_surrogate_loss(const torch::Tensor& ratio, const torch::Tensor& behaviour_weight, const torch::Tensor& advantage,
                                       double clip) {
  const torch::Tensor unclipped = ratio * advantage;
  const torch::Tensor clipped = torch::clamp(ratio, 1.0 - clip, 1.0 + clip) * advantage;
  return -(behaviour_weight * torch::min(unclipped, clipped)).mean();
}

double clip_fraction(const torch::Tensor& ratio, double clip) {
  return ((ratio - 1.0).abs() > clip).to(torch::kFloat64).mean().item<double>();
}

torch::Tensor value_loss(const torch::Tensor& value, const torch::Tensor& old_value, const torch::Tensor& target, double clip) {
  const torch::Tensor plain = (value - target).pow(2);
  if (clip <= 0) return 0.5 * plain.mean();
  const torch::Tensor clipped = (old_value + torch::clamp(value - old_value, -clip, clip) - target).pow(2);
  return 0.5 * torch::max(plain, clipped).mean();
}

double explained_variance(const torch::Tensor& prediction, const torch::Tensor& target) {
  const double var = target.to(torch::kFloat64).var(/*unbiased=*/false).item<double>();
  if (!(var > 0)) return 0.0;
  return 1.0 - (target - prediction).to(torch::kFloat64).var(false).item<double>() / var;
}

void KlController::update(double kl) {
  if (kl < target_ / 1.5)
    beta_ /= 2.0;
  else if (kl > target_ * 1.5)
    beta_ *= 2.0;
}

}  // namespace mimic
