// Vectorised collection: episode boundaries, failure vs truncation, bootstrap values, history
// stacking, episodes mode and independence from the thread count.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "learn/ppo/collector.hpp"
#include "toy_env.hpp"

using namespace mimic;
using mimic::test::ToyEnv;

namespace {

struct Nets {
  GaussianPolicy policy{nullptr};
  ValueNet value{nullptr};
  explicit Nets(int input, int history = 1) {
    torch::manual_seed(3);
    PolicyConfig pc;
    pc.net.hidden = {8};
    pc.net.history = history;
    NetworkConfig vc;
    vc.hidden = {8};
    vc.history = history;
    vc.gru_size = pc.net.gru_size = 4;
    policy = GaussianPolicy(input, 1, pc);
    value = ValueNet(input, vc);
  }
  float v(std::vector<float> input) {
    torch::NoGradGuard g;
    return value->forward(torch::tensor(input).view({1, -1})).item<float>();
  }
};

}  // namespace

TEST(Collector, MarksEndingsAndBootstrapsTruncationsWithTheLastObservation) {
  Collector c([] { return std::make_unique<ToyEnv>(3, 0); }, 2, 1, 1, 1);
  Nets nets(2);
  RunningNormalizer norm(2);
  std::mt19937_64 rng(1);
  const Rollout r = c.collect_steps(4, nets.policy, nets.value, norm, rng);
  ASSERT_EQ(r.size(), 8);
  ASSERT_EQ(r.env_steps.size(), 2u);
  for (const auto& idx : r.env_steps) {
    ASSERT_EQ(idx.size(), 4u);
    // Steps 1..3 are an episode cut by the time limit; step 4 starts the next one.
    EXPECT_FALSE(r.ended[static_cast<std::size_t>(idx[0])]);
    EXPECT_TRUE(r.ended[static_cast<std::size_t>(idx[2])]);
    EXPECT_FALSE(r.failed[static_cast<std::size_t>(idx[2])]);
    EXPECT_FALSE(r.ended[static_cast<std::size_t>(idx[3])]);
    // The observation the policy saw: (t / 10, 1).
    EXPECT_DOUBLE_EQ(r.frame(idx[1])[0], 0.1);
    EXPECT_DOUBLE_EQ(r.frame(idx[3])[0], 0.0);
    EXPECT_DOUBLE_EQ(r.next_frame(idx[2])[0], 0.3);  // the episode's last observation
    // Inside an episode the next value is the next sample's value; a truncation is bootstrapped
    // with V(last observation), and so is the horizon's last step with V(current observation).
    EXPECT_FLOAT_EQ(static_cast<float>(r.next_value[static_cast<std::size_t>(idx[0])]), r.value[static_cast<std::size_t>(idx[1])]);
    EXPECT_NEAR(r.next_value[static_cast<std::size_t>(idx[2])], nets.v({0.3f, 1.f}), 1e-6);
    EXPECT_NEAR(r.next_value[static_cast<std::size_t>(idx[3])], nets.v({0.1f, 1.f}), 1e-6);
  }
  // What the environment reports besides its reward is summed apart: steps 1, 2, 3, 1 in each.
  ASSERT_EQ(r.info_sums.size(), 1u);
  EXPECT_EQ(r.info_sums[0].first, "step");
  EXPECT_DOUBLE_EQ(r.info_sums[0].second, 2 * 7.0);
  ASSERT_EQ(r.term_sums.size(), 1u);
  EXPECT_EQ(r.term_sums[0].first, "toy");
  const EpisodeStats s = c.take_episode_stats();
  EXPECT_EQ(s.returns.size(), 2u);
  EXPECT_EQ(s.lengths, (std::vector<int>{3, 3}));
  EXPECT_EQ(s.failures, 0);
}

TEST(Collector, FailuresAreCutOffNotBootstrapped) {
  Collector c([] { return std::make_unique<ToyEnv>(10, 2); }, 1, 1, 1, 1);
  Nets nets(2);
  RunningNormalizer norm(2);
  std::mt19937_64 rng(1);
  const Rollout r = c.collect_steps(3, nets.policy, nets.value, norm, rng);
  EXPECT_TRUE(r.ended[1]);
  EXPECT_TRUE(r.failed[1]);
  EXPECT_EQ(c.take_episode_stats().failures, 1);
}

TEST(Collector, StacksHistoryFramesRepeatingTheFirstAtAReset) {
  Collector c([] { return std::make_unique<ToyEnv>(5); }, 1, 1, 3, 1);
  EXPECT_EQ(c.input_size(), 6);
  Nets nets(6, 3);
  RunningNormalizer norm(6);
  std::mt19937_64 rng(1);
  const Rollout r = c.collect_steps(3, nets.policy, nets.value, norm, rng);
  auto input = [&](int i) { return std::vector<double>(r.raw_input.begin() + i * 6, r.raw_input.begin() + i * 6 + 6); };
  EXPECT_EQ(input(0), (std::vector<double>{0, 1, 0, 1, 0, 1}));
  EXPECT_EQ(input(2), (std::vector<double>{0, 1, 0.1, 1, 0.2, 1}));  // oldest frame first
}

TEST(Collector, EpisodesModeCollectsExactlyTheRequestedCompleteEpisodes) {
  Collector c([] { return std::make_unique<ToyEnv>(4); }, 3, 2, 1, 1);
  Nets nets(2);
  RunningNormalizer norm(2);
  std::mt19937_64 rng(1);
  const Rollout r = c.collect_episodes(7, nets.policy, nets.value, norm, rng);
  EXPECT_EQ(r.size(), 28);
  int ended = 0;
  for (auto e : r.ended) ended += e;
  EXPECT_EQ(ended, 7);
  for (const auto& idx : r.env_steps) EXPECT_TRUE(idx.empty() || r.ended[static_cast<std::size_t>(idx.back())]);
  EXPECT_EQ(c.take_episode_stats().returns.size(), 7u);
}

TEST(Collector, RolloutsDoNotDependOnTheThreadCount) {
  auto run = [](int threads) {
    Collector c([] { return std::make_unique<ToyEnv>(5); }, 6, threads, 1, 9);
    Nets nets(2);
    RunningNormalizer norm(2);
    std::mt19937_64 rng(4);
    return c.collect_steps(7, nets.policy, nets.value, norm, rng);
  };
  const Rollout a = run(1), b = run(3);
  EXPECT_EQ(a.action, b.action);
  EXPECT_EQ(a.env_reward, b.env_reward);
  EXPECT_EQ(a.next_value, b.next_value);
}

TEST(Collector, RejectsNonFiniteRewardsNamingTheEnvironment) {
  Collector c([] { return std::make_unique<ToyEnv>(10, 0, 2); }, 1, 1, 1, 1);
  Nets nets(2);
  RunningNormalizer norm(2);
  std::mt19937_64 rng(1);
  try {
    (void)c.collect_steps(3, nets.policy, nets.value, norm, rng);
    FAIL() << "no error";
  } catch (const mimic::Error& e) {
    EXPECT_NE(std::string(e.what()).find("environment 0: non-finite reward at step 2"), std::string::npos) << e.what();
  }
}
