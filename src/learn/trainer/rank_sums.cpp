#include "learn/trainer/rank_sums.hpp"

#include <span>
#include <string>

#include "core/error.hpp"

namespace mimic {

void average_gradients(const std::vector<torch::Tensor>& params, ranks::Channel channel) {
  if (!ranks::many()) return;
  std::vector<torch::Tensor> grads;
  for (const auto& p : params)
    if (p.grad().defined()) grads.push_back(p.grad());
  if (grads.empty()) return;
  std::vector<torch::Tensor> flat_parts;
  for (const auto& g : grads) flat_parts.push_back(g.reshape({-1}).to(torch::kFloat32));
  torch::Tensor flat = torch::cat(flat_parts).contiguous();
  ranks::sum(std::span<float>(flat.data_ptr<float>(), static_cast<std::size_t>(flat.numel())), channel);
  flat.div_(static_cast<double>(ranks::size()));
  std::int64_t at = 0;
  torch::NoGradGuard no_grad;
  for (auto& g : grads) {
    g.copy_(flat.slice(0, at, at + g.numel()).view_as(g));
    at += g.numel();
  }
}

double mean_over_ranks(double value, ranks::Channel channel) {
  return ranks::many() ? ranks::sum(value, channel) / ranks::size() : value;
}

void update_over_ranks(RunningNormalizer& norm, const Eigen::MatrixXd& samples) {
  if (!ranks::many()) {
    norm.update(samples);
    return;
  }
  const Eigen::Index width = norm.size();
  if (samples.rows() > 0 && samples.cols() != width)
    throw Error("normalizer: samples have " + std::to_string(samples.cols()) + " values, expected " + std::to_string(width));
  RunningNormalizer mine(static_cast<int>(width), norm.clip(), norm.epsilon());
  mine.update(samples);  // this rank's count, mean and m2 (checks the values)
  // The count and the sum, hence the mean of all; then each part's m2 about that mean.
  const double n = ranks::sum(mine.count());
  if (n <= 0) return;
  Eigen::VectorXd weighted = mine.count() * mine.mean();
  ranks::sum(std::span<double>(weighted.data(), static_cast<std::size_t>(width)));
  const Eigen::VectorXd mean = weighted / n;
  Eigen::VectorXd m2(width);
  for (Eigen::Index j = 0; j < width; ++j) m2[j] = mine.m2()[j] + mine.count() * (mine.mean()[j] - mean[j]) * (mine.mean()[j] - mean[j]);
  ranks::sum(std::span<double>(m2.data(), static_cast<std::size_t>(width)));
  RunningNormalizer all(static_cast<int>(width), norm.clip(), norm.epsilon());
  all.set_state(n, mean, m2);
  norm.merge(all);
}

Moments moments_over_ranks(const torch::Tensor& rows_in) {
  const torch::Tensor rows = rows_in.to(torch::kFloat64).contiguous();
  const std::int64_t width = rows.size(1);
  torch::Tensor first = torch::cat({torch::full({1}, static_cast<double>(rows.size(0)), torch::kFloat64), rows.sum(0)}).contiguous();
  ranks::sum(std::span<double>(first.data_ptr<double>(), static_cast<std::size_t>(first.numel())));
  const double n = first[0].item<double>();
  const torch::Tensor mean = n > 0 ? first.slice(0, 1) / n : torch::zeros({width}, torch::kFloat64);
  torch::Tensor m2 = (rows - mean).square().sum(0).contiguous();
  ranks::sum(std::span<double>(m2.data_ptr<double>(), static_cast<std::size_t>(m2.numel())));
  const torch::Tensor var = n > 1 ? m2 / (n - 1) : torch::zeros_like(m2);
  return {mean.to(torch::kFloat32), var.to(torch::kFloat32), n};
}

}  // namespace mimic
