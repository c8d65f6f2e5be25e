#pragma once
// Discriminators for adversarial imitation. One network with N output heads over shared layers:
// N = 1 with binary cross-entropy is GAIL's discriminator (seeds 000, 002); N = 32 with hinge
// loss and a gradient penalty is ICCGAN's ensemble (seed 004 eqs. 2-5). Inputs are standardised
// by statistics of the expert features (or of their mixture with the replay pool, renewed at each
// update), saved with the network.
#include <torch/torch.h>

#include <functional>
#include <limits>
#include <random>

#include "learn/networks/networks.hpp"

namespace mimic {

struct DiscriminatorConfig {
  DiscriminatorConfig() { net.hidden = {100, 100}; }  // seed 002 A.3
  NetworkConfig net;
  std::string loss = "bce";       // bce (GAIL) | hinge (ICCGAN)
  int heads = 1;                  // N; the reward averages over them
  double gradient_penalty = 0.0;  // lambda_GP on interpolates of expert and policy samples
  // Heads whose penalty each minibatch takes, drawn anew each time (0: all). The penalty costs one
  // double backward per head; a random subset is an unbiased estimate of eq. 4's mean over heads.
  int penalty_heads = 0;
  // Whose gradient the penalty holds near norm 1: "heads" (seed 004 eq. 3, each head's own, averaged)
  // or "sum" (the gradient of the heads' sum, as seed 004's released code computes it: one double
  // backward, and N heads that agree each keep a slope near 1/N, so a policy sample a few
  // standardised units from the demonstrations is not yet scored below -1 by all of them).
  std::string penalty_of = "heads";
  double lr = 3e-4;
  int epochs = 2;                 // passes per iteration over as many samples as the iteration collected
  int batch = 256;                // policy samples per minibatch (and as many expert samples)
  int replay = 0;                 // policy samples kept across iterations (0: this iteration's only)
  // bce: what a sample earns from D = sigmoid(logit). "neg_log_one_minus_d", -log(1 - D) (seed 000:
  // never negative, so surviving pays) clipped above at reward_clip; "log_d", log D (never positive,
  // so ending an episode pays unless reward_offset makes up for it) clipped below at -reward_clip;
  // "logit", log D - log(1 - D), clipped to +-reward_clip: the sum of both, whose slope does not
  // vanish where the discriminator is sure (D near 0 or 1).
  std::string reward = "neg_log_one_minus_d";
  double reward_clip = 10.0;
  double reward_offset = 0.0;     // added to every reward: 1 keeps the hinge ensemble's [-1, 1] non-negative,
                                  // so that ending an episode early never pays
  // Input statistics: "expert" (the demonstrations') or "mixture" (half demonstrations, half the
  // replay pool: the distribution each minibatch is drawn from, renewed at every update). With
  // expert statistics a feature the clip barely varies is blown up on the policy's side, the
  // ensemble scores every policy sample far below -1 and the clipped reward goes flat.
  std::string standardise = "expert";
  // Mismatched samples (set_mismatched) drawn per policy sample of a minibatch and labelled as the
  // policy's (0: none).
  double mismatched = 0.0;
};

// Losses on [batch, heads] outputs, averaged over heads.
// Binary cross-entropy on logits, expert labelled 1 and policy 0.
torch::Tensor bce_loss(const torch::Tensor& expert_logits, const torch::Tensor& policy_logits);
// Seed 004 eq. 2: E[max(0, 1 + D(policy))] + E[max(0, 1 - D(expert))].
torch::Tensor hinge_loss(const torch::Tensor& expert_scores, const torch::Tensor& policy_scores);
// Seed 004 eq. 3: mean over heads of E[(|grad_x D_i(x)| - 1)^2] at `points` (with a graph, so the
// penalty trains the network: double backward); over the listed heads only when `heads` is given.
torch::Tensor gradient_penalty(FeatureNet& net, const torch::Tensor& points, const std::vector<std::int64_t>& heads = {});
// E[(|grad_x sum_i D_i(x)| - 1)^2] at `points`, with a graph (penalty_of: sum).
torch::Tensor summed_gradient_penalty(FeatureNet& net, const torch::Tensor& points);
// Per-sample rewards [batch] from [batch, heads] outputs, averaged over heads. GAIL's, by `form`
// (DiscriminatorConfig::reward): -log(1 - sigmoid(logit)) = softplus(logit) clipped at `clip`;
// log sigmoid(logit) = -softplus(-logit) clipped at -clip; or the logit clipped to +-clip.
// ICCGAN's: the mean over heads of clip(D_i, -1, 1) (seed 004 eq. 5).
torch::Tensor gail_reward(const torch::Tensor& logits, double clip, const std::string& form = "neg_log_one_minus_d");
torch::Tensor ensemble_reward(const torch::Tensor& scores);

struct DiscriminatorStats {
  double loss = 0, penalty = 0;
  // Before the update, on this iteration's policy samples and as many expert samples: fraction
  // classified correctly (expert D > 0, policy D < 0; averaged over heads) and mean outputs.
  double expert_accuracy = 0, policy_accuracy = 0, expert_score = 0, policy_score = 0;
  // The same on as many mismatched samples, when the discriminator has them (else NaN).
  double mismatched_accuracy = std::numeric_limits<double>::quiet_NaN(), mismatched_score = std::numeric_limits<double>::quiet_NaN();
};

class Discriminator {
 public:
  // `expert` [samples, input]: the features it learns to tell apart, also the source of the
  // standardisation statistics (with the policy's, under "mixture").
  Discriminator(torch::Tensor expert, const DiscriminatorConfig& cfg, std::uint64_t seed);

  int input_size() const { return static_cast<int>(expert_.size(1)); }
  const torch::Tensor& expert() const { return expert_; }  // [samples, input], as given
  const DiscriminatorConfig& config() const { return cfg_; }
  // Expert features that belong to another behaviour context (another context's demonstrations,
  // or their one-hot set to a context not theirs): a matching-aware discriminator (Reed et al.
  // 2016, GAN-CLS) learns to score them as the policy's, so that acting out one context's
  // behaviour under another's earns the policy nothing. Used when config().mismatched > 0; an
  // empty tensor clears them. Error on another width.
  void set_mismatched(torch::Tensor rows);
  const torch::Tensor& mismatched() const { return mismatched_; }
  // Raw outputs [batch, heads] for unstandardised features [batch, input].
  torch::Tensor forward(const torch::Tensor& features);
  // Per-sample reward [batch] by the configured loss's rule (no gradients).
  torch::Tensor reward(const torch::Tensor& features);
  // M epochs on the newest policy features [samples, input] (joined to the replay buffer).
  // TrainingDiverged as soon as a loss or the penalty is NaN or infinite, or after the update a
  // weight is (or has exploded); either leaves the network part-updated, not to be saved.
  DiscriminatorStats update(const torch::Tensor& policy);

  FeatureNet& net() { return net_; }
  const FeatureNet& net() const { return net_; }
  // The standardisation of its inputs: (x - mean) / std, each [input].
  const torch::Tensor& input_mean() const { return mean_; }
  const torch::Tensor& input_std() const { return std_; }
  // update() polls it between minibatches and throws Interrupted once it returns true.
  void set_interrupt(std::function<bool()> interrupted) { interrupted_ = std::move(interrupted); }
  // TrainingDiverged naming the first weight that is NaN, infinite or exploded.
  void check_weights() const;
  std::int64_t replay_rows() const { return replay_.size(0); }
  // Forgets what only further training needs (Adam moments, the replay pool): for an exported model.
  void drop_training_state();
  void save(torch::serialize::OutputArchive& a) const;
  void load(torch::serialize::InputArchive& a);
  // load() of a discriminator saved with fewer inputs, each at its place in `kept`
  // (input_widening.hpp): new inputs get zero weights and this expert's statistics; the Adam
  // moments and the replay pool, of the narrower features, start afresh.
  void load_widened(torch::serialize::InputArchive& a, const std::vector<std::int64_t>& kept);

 private:
  torch::Tensor standardise(const torch::Tensor& x) const { return (x - mean_) / std_; }
  torch::Tensor loss_of(const torch::Tensor& expert_out, const torch::Tensor& policy_out) const;
  // Sets mean_ and std_ from the expert's moments, mixed half and half with `policy`'s when defined.
  void set_statistics(const torch::Tensor& policy);

  DiscriminatorConfig cfg_;
  torch::Tensor expert_, mean_, std_;
  torch::Tensor mismatched_;  // [rows, input], possibly none
  torch::Tensor replay_;  // [kept, input]
  FeatureNet net_{nullptr};
  std::unique_ptr<torch::optim::Adam> optimizer_;
  std::mt19937_64 rng_;  // minibatches, expert draws, interpolation coefficients
  std::function<bool()> interrupted_;
};

}  // namespace mimic
