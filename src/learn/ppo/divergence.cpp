#include "learn/ppo/divergence.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mimic {

void check_diverged(double v, double lo, double hi, const std::string& where, const std::string& what) {
  if (v >= lo && v <= hi) return;
  const std::string value = std::isnan(v) ? "NaN" : std::isinf(v) ? (v > 0 ? "infinite" : "-infinite") : fmt::format("{:.4g}", v);
  const std::string bound = std::isnan(v) || std::isinf(v) ? "" : v > hi ? fmt::format(", above {:g}", hi) : fmt::format(", below {:g}", lo);
  throw TrainingDiverged(fmt::format("{}: {} is {}{}; {}", where, what, value, bound, divergence::kStopping));
}

void check_weights(const torch::nn::Module& net, const std::string& name, const std::string& where) {
  torch::NoGradGuard no_grad;
  for (const auto& p : net.named_parameters()) {
    if (p.value().numel() == 0) continue;
    // max propagates NaN and infinity: one pass over the weights tells all three cases apart.
    const double largest = p.value().detach().abs().max().item<double>();
    if (!std::isfinite(largest))
      throw TrainingDiverged(fmt::format("{}: parameter '{}.{}' holds NaN or infinity; {}", where, name, p.key(), divergence::kStopping));
    if (largest > divergence::kMaxWeight)
      throw TrainingDiverged(fmt::format("{}: parameter '{}.{}' has exploded (a weight of {:.3g}, above {:g}); {}", where, name, p.key(),
                                         largest, divergence::kMaxWeight, divergence::kStopping));
  }
}

}  // namespace mimic
