#pragma once
// What the ranks' copies of the learner must agree on (ranks.hpp), summed over the ranks: with
// one rank each function is what a single process does.
#include <torch/torch.h>

#include <utility>
#include <vector>

#include "learn/networks/normalizer.hpp"
#include "learn/trainer/ranks.hpp"

namespace mimic {

// Every parameter's gradient becomes the mean of the ranks' (each rank's minibatch is one Nth of
// the learner's), so that identical copies take identical steps.
void average_gradients(const std::vector<torch::Tensor>& params, ranks::Channel channel);
// The mean over the ranks of a value each has (a loss, a KL).
double mean_over_ranks(double value, ranks::Channel channel);
// `samples` of every rank added to `norm`: the ranks' batches merged by Chan et al.'s formula, so
// that every copy holds the statistics of all the samples.
void update_over_ranks(RunningNormalizer& norm, const Eigen::MatrixXd& samples);
// Column means and unbiased variances of every rank's `rows` together (rows of one width), and
// how many rows that was.
struct Moments {
  torch::Tensor mean, variance;
  double count = 0;
};
Moments moments_over_ranks(const torch::Tensor& rows);

}  // namespace mimic
