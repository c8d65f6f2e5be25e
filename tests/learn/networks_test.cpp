// Networks: initialisers, the fixed-covariance policy, the recurrent variant, parameter counts,
// learning-rate schedules.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "learn/networks/networks.hpp"
#include "learn/ppo/ppo.hpp"

using namespace mimic;

TEST(Networks, TruncatedNormalStaysWithinTwoSigmaWithTheExpectedSpread) {
  torch::manual_seed(1);
  torch::Tensor t = torch::empty({200, 200});
  truncated_normal_(t, 0.05);
  EXPECT_LE(t.abs().max().item<double>(), 0.1 + 1e-7);
  // A normal truncated at 2 sigma has std 0.8796 sigma.
  EXPECT_NEAR(t.std().item<double>(), 0.8796 * 0.05, 0.001);
  EXPECT_NEAR(t.mean().item<double>(), 0.0, 0.001);
}

TEST(Networks, OrthogonalLayersAndParameterCounts) {
  torch::manual_seed(2);
  PolicyConfig pc;
  pc.net.hidden = {1024, 512};
  pc.net.activation = "relu";
  GaussianPolicy policy(197, 36, pc);
  // 197*1024 + 1024 + 1024*512 + 512 + 512*36 + 36 weights and biases, + 36 log sigmas.
  EXPECT_EQ(parameter_count(*policy), 197 * 1024 + 1024 + 1024 * 512 + 512 + 512 * 36 + 36 + 36);
  // The first layer's rows are orthogonal with gain sqrt(2) (ReLU): W W^T = 2 I (197 < 1024 rows:
  // the columns are orthonormal instead, W^T W = 2 I).
  const torch::Tensor w = policy->named_parameters()["net.layers.0.weight"];
  ASSERT_EQ(w.size(0), 1024);
  EXPECT_TRUE(torch::allclose(w.t().mm(w), 2.0 * torch::eye(197), 1e-4, 1e-4));
  // The output layer's gain is 0.01: the initial mean action is close to zero.
  const auto [mean, log_std] = policy->forward(torch::randn({8, 197}));
  EXPECT_LT(mean.abs().max().item<double>(), 0.5);
  EXPECT_TRUE(torch::allclose(log_std, torch::full({8, 36}, -1.0)));
}

TEST(Networks, FixedCovarianceIsNotTrained) {
  PolicyConfig pc;
  pc.learn_std = false;
  pc.log_std = -2.0;
  GaussianPolicy policy(3, 2, pc);
  EXPECT_FALSE(policy->log_std().requires_grad());
  auto [mean, log_std] = policy->forward(torch::randn({4, 3}));
  (mean.sum() + log_std.sum()).backward();
  EXPECT_FALSE(policy->log_std().grad().defined());
}

TEST(Networks, RecurrentVariantReadsFramesInOrder) {
  torch::manual_seed(3);
  PolicyConfig pc;
  pc.net.hidden = {16};
  pc.net.history = 4;
  pc.net.gru_size = 8;
  pc.net.output_scale = 1.0;
  GaussianPolicy policy(4 * 5, 3, pc);
  NetworkConfig vc = pc.net;
  ValueNet value(4 * 5, vc);
  const torch::Tensor x = torch::randn({2, 20});
  const auto [mean, log_std] = policy->forward(x);
  EXPECT_EQ(mean.sizes(), (std::vector<std::int64_t>{2, 3}));
  EXPECT_EQ(value->forward(x).sizes(), (std::vector<std::int64_t>{2}));
  // Reversing the frames changes the output (a GRU is not a bag of frames).
  const torch::Tensor reversed = x.view({2, 4, 5}).flip({1}).reshape({2, 20});
  EXPECT_FALSE(torch::allclose(policy->forward(reversed).first, mean));
  EXPECT_THROW(GaussianPolicy(21, 3, pc), mimic::Error);  // 21 values are not 4 frames
}

TEST(Networks, AFixedCovarianceAnnealsToItsFinalLogStd) {
  TrainConfig c;
  c.policy.learn_std = false;
  c.policy.log_std = -1.0;
  c.policy.log_std_final = -2.5;
  PpoLearner ppo(3, 2, c);
  auto log_std = [&] { return ppo.policy()->forward(torch::zeros({1, 3})).second; };
  ppo.set_progress(0.0);
  EXPECT_TRUE(torch::allclose(log_std(), torch::full({1, 2}, -1.0)));
  ppo.set_progress(0.4);  // -1 + 0.4 * (-1.5)
  EXPECT_TRUE(torch::allclose(log_std(), torch::full({1, 2}, -1.6)));
  ppo.set_progress(1.7);  // held at the final value past the run's end
  EXPECT_TRUE(torch::allclose(log_std(), torch::full({1, 2}, -2.5)));
  EXPECT_FALSE(ppo.policy()->log_std().requires_grad());
  // Without a final value the covariance stays where it started.
  c.policy.log_std_final = std::numeric_limits<double>::quiet_NaN();
  PpoLearner fixed(3, 2, c);
  fixed.set_progress(0.9);
  EXPECT_TRUE(torch::allclose(fixed.policy()->forward(torch::zeros({1, 3})).second, torch::full({1, 2}, -1.0)));
}

TEST(Networks, LinearScheduleAndSgdWithMomentum) {
  TrainConfig c;
  c.optimizer.schedule = "linear";
  c.optimizer.final_fraction = 0.1;
  c.optimizer.policy_lr = 1e-3;
  c.optimizer.value_lr = 2e-3;
  PpoLearner adam(3, 1, c);
  adam.set_progress(0.5);
  auto lr = [](torch::optim::Optimizer& o) { return o.param_groups().front().options().get_lr(); };
  EXPECT_DOUBLE_EQ(lr(adam.policy_optimizer()), 1e-3 * (1 - 0.9 * 0.5));
  EXPECT_DOUBLE_EQ(lr(adam.value_optimizer()), 2e-3 * (1 - 0.9 * 0.5));
  adam.set_progress(1.0);
  EXPECT_DOUBLE_EQ(lr(adam.policy_optimizer()), 1e-4);
  c.optimizer.kind = "sgd";
  c.optimizer.momentum = 0.8;
  PpoLearner sgd(3, 1, c);
  auto* opt = dynamic_cast<torch::optim::SGD*>(&sgd.policy_optimizer());
  ASSERT_NE(opt, nullptr);
  EXPECT_DOUBLE_EQ(static_cast<torch::optim::SGDOptions&>(opt->param_groups().front().options()).momentum(), 0.8);
}
