// PPO's loss pieces and the adaptive KL rule against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>

#include "learn/ppo/ppo_loss.hpp"

using namespace mimic;

namespace {
torch::Tensor t(std::vector<float> v) { return torch::tensor(v); }
double v(const torch::Tensor& x) { return x.item<double>(); }
const double kLn2 = std::log(2.0), kHalfLog2PiE = 0.5 * std::log(2.0 * M_PI) + 0.5;
}  // namespace

TEST(PpoLoss, ClippedSurrogateTakesThePessimisticTerm) {
  // eps 0.2: (0.5, A=1) -> 0.5; (1.0, A=-1) -> -1; (1.5, A=2) -> 1.2*2 = 2.4; (0.5, A=-1) -> 0.8*-1 = -0.8.
  const torch::Tensor ratio = t({0.5f, 1.0f, 1.5f, 0.5f}), adv = t({1.f, -1.f, 2.f, -1.f});
  EXPECT_NEAR(v(clipped_surrogate_loss(ratio, adv, 0.2)), -(0.5 - 1.0 + 2.4 - 0.8) / 4, 1e-6);
  EXPECT_NEAR(clip_fraction(ratio, 0.2), 0.75, 1e-12);
  // Without clipping (huge eps) it is the plain importance-weighted advantage.
  EXPECT_NEAR(v(clipped_surrogate_loss(ratio, adv, 100.0)), -(0.5 - 1.0 + 3.0 - 0.5) / 4, 1e-6);
}

TEST(PpoLoss, DecoupledSurrogateWeighsEachSampleByProximalOverBehaviourProbability) {
  // The pessimistic terms as above (0.5, -1, 2.4, -0.8) weighted by (2, 1, 0.5, 0):
  // 1 - 1 + 1.2 + 0 = 1.2 over 4 samples.
  const torch::Tensor ratio = t({0.5f, 1.0f, 1.5f, 0.5f}), adv = t({1.f, -1.f, 2.f, -1.f}), w = t({2.f, 1.f, 0.5f, 0.f});
  EXPECT_NEAR(v(decoupled_surrogate_loss(ratio, w, adv, 0.2)), -1.2 / 4, 1e-6);
  // Weights of one: the clipped surrogate itself.
  EXPECT_NEAR(v(decoupled_surrogate_loss(ratio, torch::ones({4}), adv, 0.2)), v(clipped_surrogate_loss(ratio, adv, 0.2)), 1e-7);
}

TEST(PpoLoss, GaussianLogProbEntropyAndKl) {
  const torch::Tensor mean = torch::zeros({1, 2}), log_std = t({0.f, static_cast<float>(kLn2)}).view({1, 2});
  const torch::Tensor a = t({1.f, 0.f}).view({1, 2});
  // dim 1: -1/2 - log sqrt(2 pi); dim 2 (sigma 2, at the mean): -ln 2 - log sqrt(2 pi).
  EXPECT_NEAR(v(gaussian_log_prob(a, mean, log_std)[0]), -0.5 - kLn2 - std::log(2.0 * M_PI), 1e-6);
  EXPECT_NEAR(v(gaussian_entropy(log_std)[0]), 2 * kHalfLog2PiE + kLn2, 1e-6);
  // KL(N(0,1) || N(1,4)) = ln 2 + (1 + 1) / 8 - 1/2, one dimension.
  const torch::Tensor kl = gaussian_kl(torch::zeros({1, 1}), torch::zeros({1, 1}), torch::ones({1, 1}), torch::full({1, 1}, kLn2));
  EXPECT_NEAR(v(kl[0]), kLn2 + 0.25 - 0.5, 1e-6);
  EXPECT_NEAR(v(gaussian_kl(mean, log_std, mean, log_std)[0]), 0.0, 1e-7);
}

TEST(PpoLoss, ValueLossClipsAroundTheOldValue) {
  const torch::Tensor value = t({1.f, 2.f}), old = t({0.f, 2.f}), target = t({2.f, 0.f});
  EXPECT_NEAR(v(value_loss(value, old, target, 0.0)), 0.5 * (1.0 + 4.0) / 2, 1e-6);
  // Clip 0.5: the first prediction counts as 0.5, whose error (1.5^2 = 2.25) is the larger.
  EXPECT_NEAR(v(value_loss(value, old, target, 0.5)), 0.5 * (2.25 + 4.0) / 2, 1e-6);
}

TEST(PpoLoss, ExplainedVariance) {
  const torch::Tensor target = t({1.f, 2.f, 3.f});
  EXPECT_NEAR(explained_variance(target, target), 1.0, 1e-9);
  EXPECT_NEAR(explained_variance(t({2.f, 2.f, 2.f}), target), 0.0, 1e-9);
  EXPECT_NEAR(explained_variance(t({0.f, 0.f, 0.f}), t({5.f, 5.f, 5.f})), 0.0, 1e-9);
}

TEST(PpoLoss, AdaptiveKlHalvesAndDoublesBetaAndStopsEpochsAtFourTimesTheTarget) {
  KlController kl(0.01, 1.0, 4.0);
  kl.update(0.005);  // < 0.01 / 1.5
  EXPECT_DOUBLE_EQ(kl.beta(), 0.5);
  kl.update(0.01);  // within [target / 1.5, 1.5 target]: unchanged
  EXPECT_DOUBLE_EQ(kl.beta(), 0.5);
  kl.update(0.016);  // > 1.5 * 0.01
  EXPECT_DOUBLE_EQ(kl.beta(), 1.0);
  kl.update(0.0067);  // just above target / 1.5 = 0.00667: unchanged
  EXPECT_DOUBLE_EQ(kl.beta(), 1.0);
  EXPECT_TRUE(kl.should_stop(0.041));
  EXPECT_FALSE(kl.should_stop(0.039));
  EXPECT_FALSE(KlController(0.01, 1.0, 0.0).should_stop(100.0));  // early stop off
}
