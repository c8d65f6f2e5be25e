#pragma once
// The pieces of PPO's objective as pure functions (seed 002 section 2.2; Schulman et al. 2017),
// each pinned by tests against hand-computed values.
#include <torch/torch.h>

namespace mimic {

// log N(a; mean, exp(log_std)^2 I), summed over action dimensions: [batch].
torch::Tensor gaussian_log_prob(const torch::Tensor& action, const torch::Tensor& mean, const torch::Tensor& log_std);
// Entropy of the diagonal Gaussian, summed over dimensions: [batch].
torch::Tensor gaussian_entropy(const torch::Tensor& log_std);
// KL(old || new) of two diagonal Gaussians, summed over dimensions: [batch].
torch::Tensor gaussian_kl(const torch::Tensor& old_mean, const torch::Tensor& old_log_std, const torch::Tensor& mean,
                          const torch::Tensor& log_std);

// -mean(min(r A, clip(r, 1 - eps, 1 + eps) A)): the loss to minimise.
torch::Tensor clipped_surrogate_loss(const torch::Tensor& ratio, const torch::Tensor& advantage, double clip);
// The same objective for samples collected by an older policy than the one the update starts
// from (collect.overlap): the ratio is to that proximal policy, which the clipping keeps the new
// one near, and each sample is weighted by proximal over behaviour probability (decoupled PPO,
// Hilton et al. 2021, "Batch size-invariance for policy optimization"):
// -mean(w min(r A, clip(r, 1 - eps, 1 + eps) A)).
torch::Tensor decoupled_surrogate_loss(const torch::Tensor& ratio, const torch::Tensor& behaviour_weight, const torch::Tensor& advantage,
                                       double clip);
// Fraction of samples whose ratio left [1 - eps, 1 + eps].
double clip_fraction(const torch::Tensor& ratio, double clip);
// 0.5 mean (v - target)^2; with clip > 0 the larger of that and the loss of
// old_value + clamp(v - old_value, -clip, clip) (PPO2's clipped value loss).
torch::Tensor value_loss(const torch::Tensor& value, const torch::Tensor& old_value, const torch::Tensor& target, double clip);
// 1 - Var(target - prediction) / Var(target); 0 when the targets do not vary.
double explained_variance(const torch::Tensor& prediction, const torch::Tensor& target);

// Adaptive KL penalty (seed 002 eq. 2.10): beta halves when KL < target / 1.5 and doubles when
// KL > 1.5 target; policy epochs stop early when KL > stop_factor * target (seed 002: 4).
class KlController {
 public:
  KlController(double target, double beta, double stop_factor) : target_(target), beta_(beta), stop_factor_(stop_factor) {}
  double beta() const { return beta_; }
  void set_beta(double b) { beta_ = b; }
  double target() const { return target_; }
  void update(double kl);
  bool should_stop(double kl) const { return stop_factor_ > 0 && kl > stop_factor_ * target_; }

 private:
  double target_, beta_, stop_factor_;
};

}  // namespace mimic
