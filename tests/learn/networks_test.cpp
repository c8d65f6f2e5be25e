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

TEST(Networks, AnEncoderReadsItsPartAndTheFirstLayerTheRestThenItsCode) {
  // Seed 002's perceptual encoder: inputs 2..4 of 6 through tanh layers 3 -> 4 -> 2; the first
  // layer reads inputs 0, 1, 5 and then the code (5 values), computed here by hand.
  NetworkConfig cfg;
  cfg.hidden = {8};
  cfg.activation = "relu";
  cfg.encoder.input = "terrain";
  cfg.encoder.hidden = {4, 2};
  resolve_encoder(cfg, {{"body", 0, 2}, {"terrain", 2, 3}, {"clock", 5, 1}}, "net.yaml");
  EXPECT_EQ(cfg.encoder.offset, 2);
  EXPECT_EQ(cfg.encoder.size, 3);
  torch::manual_seed(2);
  FeatureNet net(6, 3, cfg);
  EXPECT_EQ(net->first_layer_width(), 5);
  EXPECT_EQ(net->first_layer_column(1), 1);
  EXPECT_EQ(net->first_layer_column(3), -1);
  EXPECT_EQ(net->first_layer_column(5), 2);
  std::string shape;
  EXPECT_EQ(feature_net_parameters(6, 3, cfg, shape), static_cast<double>(parameter_count(*net)));
  EXPECT_EQ(shape, "6 (3 terrain -> 4 -> 2) -> 8 -> 3");
  const torch::Tensor x = torch::randn({5, 6});
  auto linear = [&](const std::string& name, const torch::Tensor& in) {
    torch::Tensor w, b;
    for (const auto& p : net->named_parameters()) {
      if (p.key() == name + ".weight") w = p.value();
      if (p.key() == name + ".bias") b = p.value();
    }
    return torch::matmul(in, w.t()) + b;
  };
  const torch::Tensor code = torch::tanh(linear("encoder.1", torch::tanh(linear("encoder.0", x.slice(1, 2, 5)))));
  const torch::Tensor first = torch::cat({x.slice(1, 0, 2), x.slice(1, 5, 6), code}, 1);
  const torch::Tensor expected = linear("layers.1", torch::relu(linear("layers.0", first)));
  EXPECT_TRUE(torch::allclose(net->forward(x), expected, 1e-5, 1e-6));
  // The encoder's part reaches the output only through the code.
  torch::Tensor other = x.clone();
  other.slice(1, 2, 5).fill_(3.0);
  EXPECT_FALSE(torch::allclose(net->forward(other), net->forward(x)));
  // Errors: a part the observation lacks (naming the parts), or a network that stacks frames.
  NetworkConfig missing = cfg;
  missing.encoder.input = "height_map";
  try {
    resolve_encoder(missing, {{"body", 0, 2}, {"clock", 2, 1}}, "net.yaml: 'policy'");
    FAIL() << "resolved a part the observation lacks";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("net.yaml: 'policy': the encoder's input 'height_map' is not a part of the observation (body, clock)"),
              std::string::npos) << e.what();
  }
  NetworkConfig stacked = cfg;
  stacked.history = 2;
  EXPECT_THROW(resolve_encoder(stacked, {{"terrain", 0, 3}}, "net.yaml"), Error);
  NetworkConfig unresolved;
  unresolved.encoder.input = "terrain";
  EXPECT_THROW(FeatureNet(6, 3, unresolved), Error);
}
