#pragma once
// A run that has diverged stops, before anything of that state is logged or saved: the last
// checkpoint stays the last good state and resumes. A quantity has diverged when it is NaN or
// infinite, or past one of these bounds, far beyond what any learning run reaches (a healthy
// PPO update moves the policy by a KL of 0.001-0.1; weights stay within tens; docs/reliability.md).
#include <torch/torch.h>

#include <limits>
#include <string>

#include "core/error.hpp"

namespace mimic {

class TrainingDiverged : public Error {
 public:
  using Error::Error;
};

namespace divergence {
inline constexpr double kMaxKl = 100.0;          // nats per sample between consecutive policies
inline constexpr double kMaxWeight = 1e6;        // any parameter of any network, in magnitude
inline constexpr double kMinLogStd = -20.0;      // the policy's log sigma (an action noise of 2e-9 ...
inline constexpr double kMaxLogStd = 10.0;       // ... to 2e4 action units)
inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();  // check_diverged's "no bound"
inline constexpr const char* kStopping = "stopping without saving (the last checkpoint is kept)";
}  // namespace divergence

// TrainingDiverged "<where>: <what> is <v>..." where `v` is NaN, infinite, or outside [lo, hi].
void check_diverged(double v, double lo, double hi, const std::string& where, const std::string& what);
// TrainingDiverged naming the first parameter of `net` (called `name` in messages) that is not
// finite or exceeds divergence::kMaxWeight in magnitude.
void check_weights(const torch::nn::Module& net, const std::string& name, const std::string& where);

}  // namespace mimic
