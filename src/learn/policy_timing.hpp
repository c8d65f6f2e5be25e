#pragma once
// The LibTorch side of `mimic bench policy`: a trained policy's mean actions and their cost, as
// the trainer computes them (observation normaliser, then the network), for comparison with the
// torch-free runtime. Free of LibTorch headers.
#include <Eigen/Core>

#include "learn/trainer.hpp"

namespace mimic {

// The policy's mean actions for raw inputs (rows), in one batch.
Eigen::MatrixXd libtorch_policy_actions(Trainer& trainer, const Eigen::MatrixXd& inputs);
// Microseconds per call of the policy mean on batches of `batch` rows taken in turn from
// `inputs`, over at least `seconds` (after a short warm-up).
double libtorch_policy_microseconds(Trainer& trainer, const Eigen::MatrixXd& inputs, int batch, double seconds);

}  // namespace mimic
