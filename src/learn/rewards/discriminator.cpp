#include "learn/rewards/discriminator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.hpp"
#include "learn/networks/archive_util.hpp"
#include "learn/ppo/divergence.hpp"
#include "learn/networks/input_widening.hpp"
#include "learn/trainer/rank_sums.hpp"

namespace mimic {

namespace {
using divergence::kUnbounded;
}  // namespace

torch::Tensor bce_loss(const torch::Tensor& expert_logits, const torch::Tensor& policy_logits) {
  namespace F = torch::nn::functional;
  return F::binary_cross_entropy_with_logits(expert_logits, torch::ones_like(expert_logits)) +
         F::binary_cross_entropy_with_logits(policy_logits, torch::zeros_like(policy_logits));
}

torch::Tensor hinge_loss(const torch::Tensor& expert_scores, const torch::Tensor& policy_scores) {
  // Means over samples and heads = (1/N) sum_i of each head's expectation.
  return torch::relu(1.0 + policy_scores).mean() + torch::relu(1.0 - expert_scores).mean();
}

torch::Tensor gradient_penalty(FeatureNet& net, const torch::Tensor& points, const std::vector<std::int64_t>& heads) {
  const torch::Tensor x = points.detach().requires_grad_(true);
  const torch::Tensor out = net->forward(x);
  std::vector<std::int64_t> all;
  if (heads.empty())
    for (std::int64_t i = 0; i < out.size(1); ++i) all.push_back(i);
  const std::vector<std::int64_t>& which = heads.empty() ? all : heads;
  torch::Tensor sum = torch::zeros({}, out.options());
  // Each head's own gradient (a gradient of the sum over heads would mix them).
  for (const std::int64_t i : which) {
    if (i < 0 || i >= out.size(1)) throw Error("gradient penalty: no head " + std::to_string(i));
    const torch::Tensor g = torch::autograd::grad({out.select(1, i).sum()}, {x}, {}, /*retain_graph=*/true, /*create_graph=*/true)[0];
    sum = sum + (g.norm(2, 1) - 1.0).square().mean();
  }
  return sum / static_cast<double>(which.size());
}

torch::Tensor summed_gradient_penalty(FeatureNet& net, const torch::Tensor& points) {
  const torch::Tensor x = points.detach().requires_grad_(true);
  const torch::Tensor g = torch::autograd::grad({net->forward(x).sum()}, {x}, {}, /*retain_graph=*/true, /*create_graph=*/true)[0];
  return (g.norm(2, 1) - 1.0).square().mean();
}

torch::Tensor gail_reward(const torch::Tensor& logits, double clip, const std::string& form) {
  namespace F = torch::nn::functional;
  if (form == "neg_log_one_minus_d") return F::softplus(logits).clamp_max(clip).mean(1);
  if (form == "log_d") return (-F::softplus(-logits)).clamp_min(-clip).mean(1);
  if (form == "logit") return logits.clamp(-clip, clip).mean(1);
  throw Error("discriminator: reward must be neg_log_one_minus_d, log_d or logit, not '" + form + "'");
}

torch::Tensor ensemble_reward(const torch::Tensor& scores) { return scores.clamp(-1.0, 1.0).mean(1); }

Discriminator::Discriminator(torch::Tensor expert, const DiscriminatorConfig& cfg, std::uint64_t seed)
    : cfg_(cfg), expert_(expert.to(torch::kFloat32).contiguous()), rng_(seed) {
  if (expert_.dim() != 2 || expert_.size(0) < 1) throw Error("discriminator: no expert samples");
  if (cfg_.heads < 1 || cfg_.batch < 1 || cfg_.epochs < 0) throw Error("discriminator: heads and batch must be positive");
  if (cfg_.penalty_heads < 0) throw Error("discriminator: penalty_heads must be >= 0 (0: every head)");
  if (cfg_.penalty_of != "heads" && cfg_.penalty_of != "sum")
    throw Error("discriminator: penalty_of must be heads or sum, not '" + cfg_.penalty_of + "'");
  if (!(cfg_.mismatched >= 0)) throw Error("discriminator: mismatched must be >= 0 (samples per policy sample)");
  if (cfg_.reward != "neg_log_one_minus_d" && cfg_.reward != "log_d" && cfg_.reward != "logit")
    throw Error("discriminator: reward must be neg_log_one_minus_d, log_d or logit, not '" + cfg_.reward + "'");
  if (cfg_.standardise != "expert" && cfg_.standardise != "mixture")
    throw Error("discriminator: standardise must be expert or mixture, not '" + cfg_.standardise + "'");
  set_statistics({});
  net_ = FeatureNet(static_cast<int>(expert_.size(1)), cfg_.heads, cfg_.net);
  optimizer_ = std::make_unique<torch::optim::Adam>(net_->parameters(), torch::optim::AdamOptions(cfg_.lr));
  replay_ = torch::empty({0, expert_.size(1)});
  mismatched_ = torch::empty({0, expert_.size(1)});
}

void Discriminator::set_mismatched(torch::Tensor rows) {
  rows = rows.to(torch::kFloat32).contiguous();
  if (rows.dim() != 2 || (rows.size(0) > 0 && rows.size(1) != expert_.size(1)))
    throw Error("discriminator: mismatched samples have " + std::to_string(rows.dim() == 2 ? rows.size(1) : 0) + " features, the expert's " +
                std::to_string(expert_.size(1)));
  mismatched_ = rows.size(0) > 0 ? rows : torch::empty({0, expert_.size(1)});
}

void Discriminator::set_statistics(const torch::Tensor& policy) {
  const auto moments = [](const torch::Tensor& x) {
    const torch::Tensor mean = x.mean(0);
    return std::pair{mean, x.size(0) > 1 ? x.var(0, /*unbiased=*/true) : torch::zeros_like(mean)};
  };
  auto [mean, var] = moments(expert_);
  // The policy's part over every rank's samples (the expert's is the same on every rank).
  const Moments over_ranks = ranks::many() && policy.defined() ? moments_over_ranks(policy) : Moments{};
  if (over_ranks.count > 0 || (!ranks::many() && policy.defined() && policy.size(0) > 0)) {
    // Moments of the equal mixture: within-part variances averaged plus the spread of the means.
    const auto [policy_mean, policy_var] = ranks::many() ? std::pair{over_ranks.mean, over_ranks.variance} : moments(policy);
    var = 0.5 * (var + policy_var) + 0.25 * (mean - policy_mean).square();
    mean = 0.5 * (mean + policy_mean);
  }
  mean_ = mean;
  // A feature that never varies keeps unit scale (no division by zero).
  const torch::Tensor sd = var.sqrt();
  std_ = torch::where(sd > 1e-6, sd, torch::ones_like(sd));
}

torch::Tensor Discriminator::forward(const torch::Tensor& features) { return net_->forward(standardise(features)); }

torch::Tensor Discriminator::reward(const torch::Tensor& features) {
  torch::NoGradGuard no_grad;
  const torch::Tensor out = forward(features);
  return (cfg_.loss == "hinge" ? ensemble_reward(out) : gail_reward(out, cfg_.reward_clip, cfg_.reward)) + cfg_.reward_offset;
}

torch::Tensor Discriminator::loss_of(const torch::Tensor& expert_out, const torch::Tensor& policy_out) const {
  return cfg_.loss == "hinge" ? hinge_loss(expert_out, policy_out) : bce_loss(expert_out, policy_out);
}

namespace {

torch::Tensor index_tensor(const std::vector<std::int64_t>& idx) {
  return torch::from_blob(const_cast<std::int64_t*>(idx.data()), {static_cast<std::int64_t>(idx.size())}, torch::kInt64).clone();
}

}  // namespace

DiscriminatorStats Discriminator::update(const torch::Tensor& policy_in) {
  const torch::Tensor policy = policy_in.to(torch::kFloat32).contiguous();
  if (policy.dim() != 2 || policy.size(1) != expert_.size(1))
    throw Error("discriminator: policy features have the wrong width");
  const std::int64_t n_new = policy.size(0);
  DiscriminatorStats s;
  if (n_new == 0 && !ranks::many()) return s;  // over several ranks this one still takes part in the sums
  // n rows of `from`, drawn with replacement.
  auto draw = [&](const torch::Tensor& from, std::int64_t n) {
    std::uniform_int_distribution<std::int64_t> pick(0, from.size(0) - 1);
    std::vector<std::int64_t> idx(static_cast<std::size_t>(n));
    for (auto& i : idx) i = pick(rng_);
    return from.index_select(0, index_tensor(idx));
  };
  auto expert_batch = [&](std::int64_t n) { return draw(expert_, n); };
  const bool with_mismatched = cfg_.mismatched > 0 && mismatched_.size(0) > 0;
  if (n_new > 0) {
    torch::NoGradGuard no_grad;
    const torch::Tensor p = forward(policy), e = forward(expert_batch(n_new));
    s.expert_accuracy = (e > 0).to(torch::kFloat32).mean().item<double>();
    s.policy_accuracy = (p < 0).to(torch::kFloat32).mean().item<double>();
    s.expert_score = e.mean().item<double>();
    s.policy_score = p.mean().item<double>();
    if (with_mismatched) {
      const torch::Tensor m = forward(draw(mismatched_, n_new));
      s.mismatched_accuracy = (m < 0).to(torch::kFloat32).mean().item<double>();
      s.mismatched_score = m.mean().item<double>();
    }
  }
  replay_ = cfg_.replay > 0 ? torch::cat({replay_, policy}).slice(0, std::max<std::int64_t>(0, replay_.size(0) + n_new - cfg_.replay))
                            : policy;
  if (cfg_.standardise == "mixture") set_statistics(replay_);
  // Every rank takes the same number of steps (a rank's share of a context's samples can differ).
  const std::int64_t pool = replay_.size(0);
  const auto per_epoch = static_cast<std::int64_t>(ranks::minimum(static_cast<double>(std::min(pool, n_new))));
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int steps = 0;
  for (int epoch = 0; epoch < cfg_.epochs; ++epoch) {
    std::vector<std::int64_t> order(static_cast<std::size_t>(pool));
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), rng_);
    for (std::int64_t start = 0; start < per_epoch; start += cfg_.batch) {
      const std::int64_t b = std::min<std::int64_t>(cfg_.batch, per_epoch - start);
      const std::vector<std::int64_t> idx(order.begin() + start, order.begin() + start + b);
      const torch::Tensor p = standardise(replay_.index_select(0, index_tensor(idx)));
      const torch::Tensor e = standardise(expert_batch(b));
      torch::Tensor fake = net_->forward(p);
      if (with_mismatched) {  // the policy's side also holds other contexts' expert samples
        const auto m = std::max<std::int64_t>(1, std::llround(cfg_.mismatched * static_cast<double>(b)));
        fake = torch::cat({fake, net_->forward(standardise(draw(mismatched_, m)))});
      }
      if (interrupted_ && interrupted_()) throw Interrupted("stopped during the discriminator's update");
      torch::Tensor loss = loss_of(net_->forward(e), fake);
      const std::string step = "discriminator step " + std::to_string(steps + 1);
      check_diverged(loss.item<double>(), -kUnbounded, kUnbounded, step, "the loss");
      s.loss += loss.item<double>();
      if (cfg_.gradient_penalty > 0) {
        std::vector<float> alpha(static_cast<std::size_t>(b));
        for (float& a : alpha) a = unit(rng_);
        const torch::Tensor a = torch::from_blob(alpha.data(), {b, 1}, torch::kFloat32).clone();
        std::vector<std::int64_t> heads;  // empty: all
        if (cfg_.penalty_of == "heads" && cfg_.penalty_heads > 0 && cfg_.penalty_heads < cfg_.heads) {
          std::vector<std::int64_t> all(static_cast<std::size_t>(cfg_.heads));
          std::iota(all.begin(), all.end(), 0);
          std::shuffle(all.begin(), all.end(), rng_);
          heads.assign(all.begin(), all.begin() + cfg_.penalty_heads);
        }
        const torch::Tensor points = a * e + (1 - a) * p;
        const torch::Tensor penalty =
            cfg_.penalty_of == "sum" ? summed_gradient_penalty(net_, points) : gradient_penalty(net_, points, heads);
        check_diverged(penalty.item<double>(), -kUnbounded, kUnbounded, step, "the gradient penalty");
        s.penalty += penalty.item<double>();
        loss = loss + cfg_.gradient_penalty * penalty;
      }
      optimizer_->zero_grad();
      loss.backward();
      average_gradients(net_->parameters(), ranks::Channel::discriminator);
      optimizer_->step();
      ++steps;
    }
  }
  if (steps > 0) s.loss /= steps, s.penalty /= steps;
  check_weights();
  return s;
}

void Discriminator::check_weights() const { mimic::check_weights(*net_, "net", "discriminator"); }

void Discriminator::drop_training_state() {
  optimizer_->state().clear();
  replay_ = torch::empty({0, expert_.size(1)});
}

void Discriminator::save(torch::serialize::OutputArchive& a) const {
  torch::serialize::OutputArchive net, opt;
  net_->save(net);
  optimizer_->save(opt);
  a.write("net", net);
  a.write("optimizer", opt);
  a.write("mean", mean_);
  a.write("std", std_);
  a.write("replay", replay_);
  a.write("rng", archive::bytes_tensor(archive::rng_text(rng_)));
}

void Discriminator::load(torch::serialize::InputArchive& a) {
  torch::serialize::InputArchive net, opt;
  a.read("net", net);
  a.read("optimizer", opt);
  net_->load(net);
  optimizer_->load(opt);
  const torch::Tensor mean = archive::get(a, "mean"), sd = archive::get(a, "std");
  if (mean.numel() != mean_.numel()) throw Error("discriminator: saved input width differs from the configured features");
  mean_ = mean, std_ = sd;
  replay_ = archive::get(a, "replay");
  archive::set_rng(rng_, archive::tensor_bytes(archive::get(a, "rng")), "discriminator");
}

void Discriminator::load_widened(torch::serialize::InputArchive& a, const std::vector<std::int64_t>& kept) {
  torch::serialize::InputArchive net;
  a.read("net", net);
  mimic::load_widened(*net_, net, kept, input_size());
  const torch::Tensor mean = archive::get(a, "mean"), sd = archive::get(a, "std");
  if (mean.dim() != 1 || mean.numel() != static_cast<std::int64_t>(kept.size()) || sd.sizes() != mean.sizes())
    throw Error("discriminator: saved statistics of " + std::to_string(mean.numel()) + " inputs, expected " + std::to_string(kept.size()));
  // The saved statistics where they were; the new inputs keep this expert's (set at construction).
  const torch::Tensor index = torch::tensor(kept, torch::kInt64);
  mean_ = mean_.clone().index_copy_(0, index, mean.to(mean_.dtype()));
  std_ = std_.clone().index_copy_(0, index, sd.to(std_.dtype()));
  optimizer_->state().clear();
  replay_ = torch::empty({0, expert_.size(1)});
  archive::set_rng(rng_, archive::tensor_bytes(archive::get(a, "rng")), "discriminator");
}

}  // namespace mimic
