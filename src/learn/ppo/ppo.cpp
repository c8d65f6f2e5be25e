#include "learn/ppo/ppo.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <limits>
#include <thread>

#include "learn/trainer/rank_sums.hpp"

namespace mimic {

namespace {

std::unique_ptr<torch::optim::Optimizer> make_optimizer(const OptimizerConfig& c, std::vector<torch::Tensor> params, double lr) {
  if (c.kind == "sgd") return std::make_unique<torch::optim::SGD>(params, torch::optim::SGDOptions(lr).momentum(c.momentum));
  return std::make_unique<torch::optim::Adam>(params, torch::optim::AdamOptions(lr).eps(c.adam_epsilon));
}

void set_lr(torch::optim::Optimizer& opt, double lr) {
  for (auto& group : opt.param_groups()) group.options().set_lr(lr);
}

double get_lr(torch::optim::Optimizer& opt) { return opt.param_groups().front().options().get_lr(); }

// Minibatches of a random permutation; the last, shorter one is kept.
std::vector<torch::Tensor> minibatches(std::int64_t n, int size, std::mt19937_64& rng) {
  std::vector<std::int64_t> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<torch::Tensor> out;
  for (std::int64_t at = 0; at < n; at += size) {
    const std::int64_t len = std::min<std::int64_t>(size, n - at);
    out.push_back(torch::from_blob(order.data() + at, {len}, torch::kInt64).clone());
  }
  return out;
}

using divergence::kUnbounded;
constexpr double kMaxBehaviourWeight = 10.0;  // decoupled PPO's proximal over behaviour probability, at most

std::string at_epoch(int iteration, int epoch) { return "iteration " + std::to_string(iteration) + ", epoch " + std::to_string(epoch + 1); }

void check_finite(const torch::Tensor& loss, const char* what, int iteration, int epoch) {
  check_diverged(loss.item<double>(), -kUnbounded, kUnbounded, at_epoch(iteration, epoch), std::string("the ") + what + " loss");
}

// The gradient's norm over `params` (clipped to `max_norm` when that is > 0); TrainingDiverged
// when it is not finite.
double clip_and_check_gradient(const std::vector<torch::Tensor>& params, double max_norm, const char* what, int iteration, int epoch) {
  const double norm = torch::nn::utils::clip_grad_norm_(params, max_norm > 0 ? max_norm : kUnbounded);
  check_diverged(norm, -kUnbounded, kUnbounded, at_epoch(iteration, epoch), std::string("the ") + what + " gradient's norm");
  return norm;
}

}  // namespace

PpoLearner::PpoLearner(int input_size, int action_size, const TrainConfig& cfg)
    : cfg_(cfg), kl_(cfg.ppo.kl_target, cfg.ppo.kl_penalty ? cfg.ppo.kl_beta : 0.0, cfg.ppo.kl_stop) {
  policy_ = GaussianPolicy(input_size, action_size, cfg.policy);
  value_ = ValueNet(input_size, cfg.value);
  policy_opt_ = make_optimizer(cfg.optimizer, policy_->parameters(), cfg.optimizer.policy_lr);
  value_opt_ = make_optimizer(cfg.optimizer, value_->parameters(), cfg.optimizer.value_lr);
}

void PpoLearner::set_progress(double progress) {
  const auto& o = cfg_.optimizer;
  const double scale = o.schedule == "linear" ? 1.0 - (1.0 - o.final_fraction) * std::clamp(progress, 0.0, 1.0) : 1.0;
  set_lr(*policy_opt_, o.policy_lr * scale);
  set_lr(*value_opt_, o.value_lr * scale);
  const PolicyConfig& pc = cfg_.policy;
  if (!pc.learn_std && std::isfinite(pc.log_std_final))
    policy_->set_log_std(pc.log_std + (pc.log_std_final - pc.log_std) * std::clamp(progress, 0.0, 1.0));
}

void PpoLearner::update_policy(const PpoBatch& b, std::mt19937_64& rng, PpoStats& s, int iteration) {
  const PpoConfig& p = cfg_.ppo;
  const torch::Tensor behaviour_log_prob = gaussian_log_prob(b.action, b.old_mean, b.old_log_std);
  // Decoupled (stale samples): the ratio and the KL to the proximal policy, each sample weighted by
  // proximal over behaviour probability (bounded: with one iteration of lag it stays near 1).
  const bool decoupled = b.prox_mean.defined();
  const torch::Tensor ref_mean = decoupled ? b.prox_mean : b.old_mean, ref_log_std = decoupled ? b.prox_log_std : b.old_log_std;
  const torch::Tensor old_log_prob = decoupled ? gaussian_log_prob(b.action, ref_mean, ref_log_std) : behaviour_log_prob;
  const torch::Tensor weight = decoupled ? torch::exp(old_log_prob - behaviour_log_prob).clamp_max(kMaxBehaviourWeight) : torch::Tensor();
  const auto params = policy_->parameters();
  for (int epoch = 0; epoch < p.epochs; ++epoch) {
    double loss_sum = 0, kl_sum = 0, ent_sum = 0, clip_sum = 0;
    int batches = 0;
    for (const torch::Tensor& idx : minibatches(b.input.size(0), p.minibatch, rng)) {
      auto [mean, log_std] = policy_->forward(b.input.index_select(0, idx));
      const torch::Tensor log_prob = gaussian_log_prob(b.action.index_select(0, idx), mean, log_std);
      const torch::Tensor ratio = torch::exp(log_prob - old_log_prob.index_select(0, idx));
      torch::Tensor adv = b.advantage.index_select(0, idx);
      const torch::Tensor kl = gaussian_kl(ref_mean.index_select(0, idx), ref_log_std.index_select(0, idx), mean, log_std).mean();
      const torch::Tensor entropy = gaussian_entropy(log_std).mean();
      torch::Tensor loss = (decoupled ? decoupled_surrogate_loss(ratio, weight.index_select(0, idx), adv, p.clip)
                                      : clipped_surrogate_loss(ratio, adv, p.clip)) -
                           p.entropy * entropy;
      if (kl_.beta() > 0) loss = loss + kl_.beta() * kl;
      check_finite(loss, "policy", iteration, epoch);
      if (interrupted_ && interrupted_()) throw Interrupted("stopped during the policy update of iteration " + std::to_string(iteration));
      policy_opt_->zero_grad();
      loss.backward();
      average_gradients(params, ranks::Channel::policy);
      s.policy_grad_norm = std::max(s.policy_grad_norm, clip_and_check_gradient(params, p.max_grad_norm, "policy", iteration, epoch));
      policy_opt_->step();
      loss_sum += loss.item<double>();
      kl_sum += kl.item<double>();
      ent_sum += entropy.item<double>();
      clip_sum += clip_fraction(ratio.detach(), p.clip);
      ++batches;
    }
    // Over all ranks: every copy must stop at the same epoch.
    s.policy_loss = mean_over_ranks(loss_sum / batches, ranks::Channel::policy);
    s.kl = mean_over_ranks(kl_sum / batches, ranks::Channel::policy);
    s.entropy = ent_sum / batches;
    s.clip_fraction = clip_sum / batches;
    s.policy_epochs = epoch + 1;
    // The early stop cannot fire on a NaN; a KL this large is a policy thrown away, not an update.
    check_diverged(s.kl, -1.0, divergence::kMaxKl, at_epoch(iteration, epoch), "the KL between the old and the new policy");
    if (kl_.should_stop(s.kl)) break;
  }
  if (cfg_.ppo.kl_penalty && s.policy_epochs > 0) kl_.update(s.kl);
  s.beta = kl_.beta();
}

void PpoLearner::update_value(const PpoBatch& b, std::mt19937_64& rng, PpoStats& s, int iteration) {
  const PpoConfig& p = cfg_.ppo;
  double value_grad_norm = 0;  // written to s at the end: the policy's thread writes s too
  const auto params = value_->parameters();
  for (int epoch = 0; epoch < p.value_epochs; ++epoch) {
    double loss_sum = 0;
    int batches = 0;
    for (const torch::Tensor& idx : minibatches(b.input.size(0), p.minibatch, rng)) {
      const torch::Tensor v = value_->forward(b.input.index_select(0, idx));
      const torch::Tensor loss = value_loss(v, b.old_value.index_select(0, idx), b.target.index_select(0, idx), p.value_clip);
      check_finite(loss, "value", iteration, epoch);
      if (interrupted_ && interrupted_()) throw Interrupted("stopped during the value update of iteration " + std::to_string(iteration));
      value_opt_->zero_grad();
      loss.backward();
      average_gradients(params, ranks::Channel::value);
      value_grad_norm = std::max(value_grad_norm, clip_and_check_gradient(params, p.max_grad_norm, "value", iteration, epoch));
      value_opt_->step();
      loss_sum += loss.item<double>();
      ++batches;
    }
    s.value_loss = loss_sum / batches;
  }
  s.value_grad_norm = value_grad_norm;
}

PpoStats PpoLearner::update(const PpoBatch& batch, std::mt19937_64& rng, bool parallel_value, int iteration) {
  PpoStats s;
  s.explained_variance = explained_variance(batch.old_value, batch.target);
  PpoBatch b = batch;
  if (cfg_.ppo.normalize_advantages && ranks::many()) {
    // By the moments of every rank's advantages, as one batch would be.
    const Moments m = moments_over_ranks(b.advantage.unsqueeze(1));
    b.advantage = (b.advantage - m.mean) / (m.variance.sqrt() + 1e-8);
  } else if (cfg_.ppo.normalize_advantages && b.advantage.size(0) > 1) {
    const torch::Tensor a = b.advantage;
    b.advantage = (a - a.mean()) / (a.std() + 1e-8);
  }
  std::mt19937_64 value_rng(rng());  // drawn first, so the order of the two updates never matters
  if (parallel_value) {
    std::exception_ptr value_error;
    std::thread value_thread([&] {
      try {
        at::set_num_threads(1);
        update_value(b, value_rng, s, iteration);
      } catch (...) {
        value_error = std::current_exception();
      }
    });
    try {
      update_policy(b, rng, s, iteration);
    } catch (...) {
      value_thread.join();
      throw;
    }
    value_thread.join();
    if (value_error) std::rethrow_exception(value_error);
  } else {
    update_policy(b, rng, s, iteration);
    update_value(b, value_rng, s, iteration);
  }
  check_parameters(iteration);
  s.policy_lr = get_lr(*policy_opt_);
  s.value_lr = get_lr(*value_opt_);
  return s;
}

void PpoLearner::check_parameters(int iteration) const {
  const std::string where = "iteration " + std::to_string(iteration);
  check_weights(*policy_, policy_->name(), where);
  check_weights(*value_, value_->name(), where);
  const torch::Tensor log_std = policy_->log_std().detach();
  if (log_std.numel() > 0) {
    check_diverged(log_std.min().item<double>(), divergence::kMinLogStd, divergence::kMaxLogStd, where, "the policy's smallest log sigma");
    check_diverged(log_std.max().item<double>(), divergence::kMinLogStd, divergence::kMaxLogStd, where, "the policy's largest log sigma");
  }
}

}  // namespace mimic
