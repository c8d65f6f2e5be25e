// Discriminator losses and rewards pinned against hand-computed values (seed 004 eqs. 2-5, seed
// 000's clipped -log(1 - D)), the gradient penalty's double backward, and the update telling
// two distributions apart.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "learn/rewards/discriminator.hpp"

using namespace mimic;

namespace {

torch::Tensor t2(std::vector<float> v, std::int64_t rows, std::int64_t cols) {
  return torch::from_blob(v.data(), {rows, cols}, torch::kFloat32).clone();
}

// One tensor of what the discriminator writes to its checkpoint.
torch::Tensor saved(const Discriminator& d, const std::string& key) {
  torch::serialize::OutputArchive out;
  d.save(out);
  std::ostringstream bytes;
  out.save_to(bytes);
  torch::serialize::InputArchive in;
  std::istringstream is(bytes.str());
  in.load_from(is);
  torch::Tensor t;
  in.read(key, t);
  return t;
}

// A linear net of two heads, D_i(x) = w_i . x + b_i with w_0 = (3, 4) and w_1 = (0.6, 0.8): the
// gradient is w_i wherever x is.
FeatureNet linear_two_head_net() {
  NetworkConfig cfg;
  cfg.hidden = {};
  FeatureNet net(2, 2, cfg);
  torch::NoGradGuard no_grad;
  net->named_parameters()["layers.0.weight"].copy_(t2({3.0f, 4.0f, 0.6f, 0.8f}, 2, 2));
  return net;
}

}  // namespace

TEST(DiscriminatorLoss, HingeIsTheMeanOverHeadsOfEachHeadsMargins) {
  // Two samples, two heads. Policy: max(0, 1 + D) = 0, 1.5 | 1, 0.5; expert: max(0, 1 - D) = 0.5, 0 | 2, 1.
  // Head 1: 0.5 + 1.25 = 1.75; head 2: 1 + 0.5 = 1.5; mean 1.625.
  const torch::Tensor expert = t2({0.5f, 2.0f, -1.0f, 0.0f}, 2, 2), policy = t2({-2.0f, 0.5f, 0.0f, -0.5f}, 2, 2);
  EXPECT_NEAR(hinge_loss(expert, policy).item<double>(), 1.625, 1e-6);
  // Samples beyond the margin on both sides cost nothing.
  EXPECT_NEAR(hinge_loss(t2({1.0f, 3.0f}, 2, 1), t2({-1.0f, -5.0f}, 2, 1)).item<double>(), 0.0, 1e-7);
}

TEST(DiscriminatorLoss, BinaryCrossEntropyLabelsExpertOneAndPolicyZero) {
  EXPECT_NEAR(bce_loss(t2({0.0f}, 1, 1), t2({0.0f}, 1, 1)).item<double>(), 2 * std::log(2.0), 1e-6);
  // -log sigmoid(1) + -log(1 - sigmoid(-1)) = 2 log(1 + e^-1).
  EXPECT_NEAR(bce_loss(t2({1.0f}, 1, 1), t2({-1.0f}, 1, 1)).item<double>(), 2 * std::log1p(std::exp(-1.0)), 1e-6);
}

TEST(DiscriminatorReward, GailIsMinusLogOneMinusDClippedAndAveragedOverHeads) {
  // D = sigmoid(0) = 1/2 gives log 2; a logit of 20 gives ~20, clipped at 10.
  const torch::Tensor r = gail_reward(t2({0.0f, 20.0f}, 2, 1), 10.0);
  EXPECT_NEAR(r[0].item<double>(), std::log(2.0), 1e-6);
  EXPECT_NEAR(r[1].item<double>(), 10.0, 1e-6);
  EXPECT_NEAR(gail_reward(t2({0.0f, 20.0f}, 1, 2), 10.0)[0].item<double>(), (std::log(2.0) + 10.0) / 2, 1e-5);
  // A very negative logit (D near 0) rewards near 0, never negative.
  EXPECT_NEAR(gail_reward(t2({-30.0f}, 1, 1), 10.0)[0].item<double>(), 0.0, 1e-9);
}

TEST(DiscriminatorReward, LogDAndTheLogitAreTheOtherForms) {
  // log sigmoid(0) = -log 2; log sigmoid(-20) = -20.000000002, clipped at -10; log sigmoid(2) = -log(1 + e^-2).
  const torch::Tensor log_d = gail_reward(t2({0.0f, -20.0f, 2.0f}, 3, 1), 10.0, "log_d");
  EXPECT_NEAR(log_d[0].item<double>(), -std::log(2.0), 1e-6);
  EXPECT_NEAR(log_d[1].item<double>(), -10.0, 1e-6);
  EXPECT_NEAR(log_d[2].item<double>(), -std::log1p(std::exp(-2.0)), 1e-6);
  // log D - log(1 - D) is the logit itself: -3 stays, 25 is clipped at 10; two heads average.
  EXPECT_NEAR(gail_reward(t2({-3.0f, 25.0f}, 1, 2), 10.0, "logit")[0].item<double>(), (-3.0 + 10.0) / 2, 1e-6);
  // Where the discriminator is sure of two policy samples, -log(1 - D) scores them alike and the
  // logit still ranks them.
  const torch::Tensor sure = t2({-12.0f, -8.0f}, 2, 1);
  const torch::Tensor flat = gail_reward(sure, 10.0), ranked = gail_reward(sure, 20.0, "logit");
  EXPECT_LT(flat[1].item<double>() - flat[0].item<double>(), 4e-4);
  EXPECT_NEAR(ranked[1].item<double>() - ranked[0].item<double>(), 4.0, 1e-6);
  EXPECT_THROW(gail_reward(sure, 10.0, "log"), Error);
  DiscriminatorConfig bad;
  bad.reward = "log";
  EXPECT_THROW(Discriminator(torch::zeros({4, 2}), bad, 1), Error);
}

TEST(DiscriminatorReward, EnsembleIsTheMeanOfHeadsClippedToPlusMinusOne) {
  const torch::Tensor r = ensemble_reward(t2({-3.0f, 0.5f, 2.0f, 0.2f, 0.4f, -0.3f}, 2, 3));
  EXPECT_NEAR(r[0].item<double>(), (-1.0 + 0.5 + 1.0) / 3, 1e-6);
  EXPECT_NEAR(r[1].item<double>(), (0.2 + 0.4 - 0.3) / 3, 1e-6);
}

TEST(GradientPenalty, EachHeadsGradientNormAgainstOneWithGradientsThroughIt) {
  FeatureNet net = linear_two_head_net();  // |w_0| = 5, |w_1| = 1
  const torch::Tensor w = net->named_parameters()["layers.0.weight"];
  const torch::Tensor points = torch::randn({7, 2});
  const torch::Tensor gp = gradient_penalty(net, points);
  EXPECT_NEAR(gp.item<double>(), ((5.0 - 1.0) * (5.0 - 1.0) + 0.0) / 2, 1e-4);
  // Double backward: d/dw_0 of (|w_0| - 1)^2 / 2 = (|w_0| - 1) w_0 / |w_0| = 4 * (0.6, 0.8); head 1 sits at its minimum.
  gp.backward();
  const torch::Tensor g = w.grad();
  EXPECT_NEAR(g[0][0].item<double>(), 2.4, 1e-4);
  EXPECT_NEAR(g[0][1].item<double>(), 3.2, 1e-4);
  EXPECT_NEAR(g[1][0].item<double>(), 0.0, 1e-5);
  EXPECT_NEAR(g[1][1].item<double>(), 0.0, 1e-5);
}

TEST(GradientPenalty, OfTheSumHoldsTheHeadsSummedGradientAgainstOne) {
  FeatureNet net = linear_two_head_net();  // summed gradient (3.6, 4.8): norm 6
  const torch::Tensor w = net->named_parameters()["layers.0.weight"];
  const torch::Tensor gp = summed_gradient_penalty(net, torch::randn({7, 2}));
  EXPECT_NEAR(gp.item<double>(), 25.0, 1e-4);  // each head's own: (16 + 0) / 2 = 8
  // d/dw_i of (|w_0 + w_1| - 1)^2 = 2 * 5 * (0.6, 0.8) for both heads.
  gp.backward();
  const torch::Tensor g = w.grad();
  for (int head = 0; head < 2; ++head) {
    EXPECT_NEAR(g[head][0].item<double>(), 6.0, 1e-4);
    EXPECT_NEAR(g[head][1].item<double>(), 8.0, 1e-4);
  }
}

TEST(Discriminator, PenaltyOfTheSumLetsAgreeingHeadsKeepASlopeNearOneOverN) {
  // Two clusters about 5.7 standardised units apart: with each head's own gradient held at 1 the
  // heads score the far side beyond -1; with the sum's, 16 agreeing heads share one unit of slope.
  torch::manual_seed(5);
  const torch::Tensor expert = torch::randn({512, 2}) + 2.0, policy = torch::randn({512, 2}) - 2.0;
  auto mean_policy_score = [&](const std::string& penalty_of) {
    DiscriminatorConfig cfg;
    cfg.loss = "hinge", cfg.heads = 16, cfg.gradient_penalty = 10.0, cfg.penalty_of = penalty_of;
    cfg.lr = 1e-3, cfg.epochs = 4, cfg.batch = 128;
    cfg.net.hidden = {32};
    Discriminator d(expert, cfg, 3);
    for (int i = 0; i < 30; ++i) d.update(policy);
    torch::NoGradGuard no_grad;
    return d.forward(policy).mean().item<double>();
  };
  const double each = mean_policy_score("heads"), sum = mean_policy_score("sum");
  std::cout << "mean policy score, penalty of each head: " << each << ", of the sum: " << sum << "\n";
  EXPECT_LT(each, -1.0);
  EXPECT_GT(sum, -1.0);
  DiscriminatorConfig bad;
  bad.penalty_of = "mean";
  EXPECT_THROW(Discriminator(expert, bad, 1), Error);
}

TEST(GradientPenalty, ASubsetOfHeadsAveragesOnlyThoseAndAllSingletonsAverageToTheFullPenalty) {
  NetworkConfig cfg;
  cfg.hidden = {};
  FeatureNet net(2, 3, cfg);
  {
    torch::NoGradGuard no_grad;
    net->named_parameters()["layers.0.weight"].copy_(t2({3.0f, 4.0f, 0.6f, 0.8f, 0.0f, 2.0f}, 3, 2));  // norms 5, 1, 2
  }
  const torch::Tensor points = torch::randn({5, 2});
  EXPECT_NEAR(gradient_penalty(net, points, {0}).item<double>(), 16.0, 1e-4);
  EXPECT_NEAR(gradient_penalty(net, points, {0, 2}).item<double>(), (16.0 + 1.0) / 2, 1e-4);
  double singles = 0;
  for (std::int64_t i = 0; i < 3; ++i) singles += gradient_penalty(net, points, {i}).item<double>() / 3;
  EXPECT_NEAR(singles, gradient_penalty(net, points).item<double>(), 1e-4);
  EXPECT_NEAR(singles, 17.0 / 3, 1e-4);
  EXPECT_THROW(gradient_penalty(net, points, {3}), Error);
}

TEST(Discriminator, PenaltyHeadsPenalisesARandomSubsetAndAllWhenAsManyAsHeads) {
  torch::manual_seed(2);
  const torch::Tensor expert = torch::randn({256, 3}) + 1.0, policy = torch::randn({256, 3}) - 1.0;
  auto penalty_with = [&](int penalty_heads) {
    DiscriminatorConfig cfg;
    cfg.loss = "hinge", cfg.heads = 8, cfg.gradient_penalty = 1.0, cfg.penalty_heads = penalty_heads;
    cfg.net.hidden = {16};
    cfg.batch = 64;
    torch::manual_seed(5);  // the same initial network each time
    Discriminator d(expert, cfg, 3);
    return d.update(policy).penalty;
  };
  const double all = penalty_with(0);
  EXPECT_EQ(penalty_with(8), all);  // as many as there are heads: every head, no draw
  const double some = penalty_with(2);
  EXPECT_GT(some, 0.0);
  EXPECT_NE(some, all);
}

TEST(Discriminator, LearnsToTellTwoDistributionsApartAndSavesExactly) {
  torch::manual_seed(1);
  const torch::Tensor expert = torch::randn({512, 3}) + 1.5, policy = torch::randn({512, 3}) - 1.5;
  for (const std::string loss : {"bce", "hinge"}) {
    DiscriminatorConfig cfg;
    cfg.loss = loss;
    cfg.heads = loss == "hinge" ? 8 : 1;
    cfg.gradient_penalty = loss == "hinge" ? 1.0 : 0.0;
    cfg.net.hidden = {16};
    cfg.lr = 3e-3;
    cfg.epochs = 5;
    cfg.batch = 64;
    Discriminator d(expert, cfg, 3);
    const DiscriminatorStats before = d.update(policy);
    DiscriminatorStats after;
    for (int i = 0; i < 5; ++i) after = d.update(policy);
    EXPECT_GT(after.expert_accuracy, 0.95) << loss;
    EXPECT_GT(after.policy_accuracy, 0.95) << loss;
    EXPECT_LT(after.loss, before.loss) << loss;
    if (loss == "hinge") {
      EXPECT_GT(after.penalty, 0.0);
    }
    if (loss == "hinge") {  // the ensemble's reward lies in [-1, 1]
      EXPECT_GE(d.reward(policy).min().item<double>(), -1.0);
      EXPECT_LE(d.reward(expert).max().item<double>(), 1.0);
    }
    // The reward ranks expert-like samples above policy-like ones.
    EXPECT_GT(d.reward(expert).mean().item<double>(), d.reward(policy).mean().item<double>() + 0.5) << loss;

    torch::serialize::OutputArchive out;
    d.save(out);
    std::ostringstream bytes;
    out.save_to(bytes);
    Discriminator e(expert, cfg, 99);
    torch::serialize::InputArchive in;
    std::istringstream is(bytes.str());
    in.load_from(is);
    e.load(in);
    EXPECT_TRUE(torch::equal(d.reward(policy), e.reward(policy))) << loss;
    // Same generator state and optimizer moments: the next update is identical too.
    d.update(policy);
    e.update(policy);
    EXPECT_TRUE(torch::equal(d.reward(expert), e.reward(expert))) << loss;
  }
}

// Mismatched samples (another context's demonstrations) join the policy's side: without them a
// discriminator that has only seen the policy on the far side scores them highest of all.
TEST(Discriminator, LearnsToScoreMismatchedSamplesAsThePolicys) {
  torch::manual_seed(4);
  const torch::Tensor expert = torch::randn({512, 2}) + torch::tensor({2.0f, 0.0f}),
                      policy = torch::randn({512, 2}) - torch::tensor({2.0f, 0.0f}),
                      other = torch::randn({512, 2}) + torch::tensor({6.0f, 0.0f});
  auto trained = [&](double mismatched) {
    DiscriminatorConfig cfg;
    cfg.loss = "hinge", cfg.heads = 4, cfg.gradient_penalty = 1.0, cfg.mismatched = mismatched;
    cfg.net.hidden = {32};
    cfg.lr = 3e-3, cfg.epochs = 5, cfg.batch = 64;
    auto d = std::make_unique<Discriminator>(expert, cfg, 3);
    d->set_mismatched(other);
    DiscriminatorStats s;
    for (int i = 0; i < 20; ++i) s = d->update(policy);
    return std::pair{std::move(d), s};
  };
  const auto [plain, plain_stats] = trained(0.0);
  const auto [matching, stats] = trained(0.5);
  const double other_plain = plain->reward(other).mean().item<double>(), other_matching = matching->reward(other).mean().item<double>();
  std::cout << "reward of the other context's samples: " << other_plain << " without them as the policy's, " << other_matching
            << " with; their accuracy " << stats.mismatched_accuracy << "\n";
  EXPECT_GT(other_plain, 0.5);
  EXPECT_LT(other_matching, -0.5);
  EXPECT_GT(stats.mismatched_accuracy, 0.9);
  EXPECT_LT(stats.mismatched_score, 0.0);
  EXPECT_TRUE(std::isnan(plain_stats.mismatched_score));  // off: not measured
  // The expert is still told from the policy.
  EXPECT_GT(matching->reward(expert).mean().item<double>(), 0.5);
  EXPECT_LT(matching->reward(policy).mean().item<double>(), -0.5);
  EXPECT_THROW(matching->set_mismatched(torch::zeros({4, 3})), Error);
  DiscriminatorConfig bad;
  bad.mismatched = -1;
  EXPECT_THROW(Discriminator(expert, bad, 1), Error);
}

TEST(Discriminator, RewardOffsetShiftsEveryReward) {
  const torch::Tensor expert = torch::randn({8, 2}), x = torch::randn({5, 2});
  DiscriminatorConfig cfg;
  cfg.loss = "hinge";
  cfg.heads = 4;
  Discriminator plain(expert, cfg, 1);
  cfg.reward_offset = 1.0;
  Discriminator shifted(expert, cfg, 1);
  {
    torch::NoGradGuard no_grad;
    auto a = plain.net()->parameters(), b = shifted.net()->parameters();
    for (std::size_t i = 0; i < a.size(); ++i) b[i].copy_(a[i]);
  }
  EXPECT_TRUE(torch::allclose(shifted.reward(x), plain.reward(x) + 1.0));
}

TEST(Discriminator, ReplayKeepsTheNewestSamplesUpToItsSize) {
  DiscriminatorConfig cfg;
  cfg.replay = 5;
  cfg.epochs = 1;
  cfg.net.hidden = {4};
  Discriminator d(torch::zeros({4, 1}), cfg, 1);  // constant expert features: unit scale, no NaN
  d.update(torch::full({3, 1}, 1.0f));
  d.update(torch::full({4, 1}, 2.0f));
  const torch::Tensor replay = saved(d, "replay");
  ASSERT_EQ(replay.size(0), 5);
  EXPECT_EQ(replay[0][0].item<float>(), 1.0f);  // the oldest surviving sample
  EXPECT_EQ(replay[4][0].item<float>(), 2.0f);
  EXPECT_TRUE(std::isfinite(d.reward(torch::ones({1, 1}))[0].item<double>()));
}

TEST(Discriminator, MixtureStandardisesByTheMinibatchDistribution) {
  // Column 0: expert {0, 2} (mean 1, variance 2), policy {4, 6, 8} (mean 6, variance 4); the equal
  // mixture has mean 3.5 and variance (2 + 4) / 2 + (6 - 1)^2 / 4 = 9.25. Column 1 never varies.
  const torch::Tensor expert = t2({0, 1, 2, 1}, 2, 2), policy = t2({4, 1, 6, 1, 8, 1}, 3, 2);
  const auto statistics = [&](const std::string& standardise) {
    DiscriminatorConfig cfg;
    cfg.standardise = standardise;
    cfg.epochs = 0;
    Discriminator d(expert, cfg, 1);
    d.update(policy);
    return std::pair{saved(d, "mean"), saved(d, "std")};
  };
  const auto [mixture_mean, mixture_std] = statistics("mixture");
  EXPECT_NEAR(mixture_mean[0].item<double>(), 3.5, 1e-6);
  EXPECT_NEAR(mixture_std[0].item<double>(), std::sqrt(9.25), 1e-5);
  EXPECT_NEAR(mixture_mean[1].item<double>(), 1.0, 1e-6);
  EXPECT_EQ(mixture_std[1].item<double>(), 1.0);  // no spread: unit scale
  const auto [expert_mean, expert_std] = statistics("expert");
  EXPECT_NEAR(expert_mean[0].item<double>(), 1.0, 1e-6);
  EXPECT_NEAR(expert_std[0].item<double>(), std::sqrt(2.0), 1e-6);

  DiscriminatorConfig bad;
  bad.standardise = "policy";
  EXPECT_THROW(Discriminator(expert, bad, 1), Error);
}

TEST(Discriminator, MixtureKeepsTheEnsemblesRewardInformativeWhereTheClipBarelyVaries) {
  // The expert holds feature 0 within 1e-4 of zero, the policy sits 0.05 away. By the expert's
  // statistics a sample 0.01 away is already 100 standard deviations out: every head scores it
  // below -1 and the clipped reward cannot tell it from the policy's. By the mixture's it can.
  torch::manual_seed(2);
  const torch::Tensor expert = torch::cat({torch::randn({512, 1}) * 1e-4, torch::randn({512, 1})}, 1);
  const torch::Tensor policy = torch::cat({torch::randn({512, 1}) * 0.01 + 0.05, torch::randn({512, 1})}, 1);
  const torch::Tensor near = t2({0.01f, 0.0f}, 1, 2), far = t2({0.05f, 0.0f}, 1, 2);
  const auto gap = [&](const std::string& standardise) {
    DiscriminatorConfig cfg;
    cfg.loss = "hinge", cfg.heads = 8, cfg.gradient_penalty = 10.0, cfg.standardise = standardise;
    cfg.net.hidden = {32, 32};
    cfg.net.activation = "relu";
    cfg.lr = 1e-3, cfg.epochs = 5, cfg.batch = 128;
    torch::manual_seed(3);
    Discriminator d(expert, cfg, 4);
    for (int i = 0; i < 10; ++i) d.update(policy);
    EXPECT_LT(d.reward(far).item<double>(), -0.3) << standardise;  // the policy's own place scores low
    return d.reward(near).item<double>() - d.reward(far).item<double>();
  };
  EXPECT_LT(gap("expert"), 0.05);
  EXPECT_GT(gap("mixture"), 0.3);
}
