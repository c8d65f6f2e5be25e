// A run that diverges stops at once with a diagnostic naming the iteration and the quantity, and
// never saves that state: the last checkpoint stays the run's and resumes.
#include <gtest/gtest.h>

#include <iostream>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "learn/rewards/adversarial_reward.hpp"
#include "learn/trainer/run_log.hpp"
#include "learn/trainer/trainer_impl.hpp"
#include "imitation_fixtures.hpp"
#include "../test_data.hpp"
#include "trainer_access.hpp"

using namespace mimic;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The message of the TrainingDiverged `f` throws ("" when it throws nothing).
template <class F>
std::string diverged(F&& f) {
  try {
    f();
  } catch (const TrainingDiverged& e) {
    return e.what();
  }
  return "";
}

}  // namespace

// Both learning rates at 10, which the config allows: the first update throws the policy away
// (its KL was 2e12 before this check, NaN from iteration 4, and the run went on to checkpoint
// thirteen poisoned iterations). Now iteration 1 stops it, and nothing of it is written.
TEST(Divergence, LearningRatesOfTenStopTheRunInItsFirstIteration) {
  const auto dir = test::temp_dir("divergence_lr10");
  const std::string text =
      "seed: 3\niterations: 20\ncheckpoint_every: 1\nenv: {name: planar_walker}\n"
      "collect: {envs: 8, threads: 1, samples: 1024}\npolicy: {hidden: [32, 32], log_std: -0.5}\nvalue: {hidden: [32, 32]}\n"
      "ppo: {epochs: 4, value_epochs: 4, minibatch: 128}\noptimizer: {policy_lr: 10, value_lr: 10}\n";
  TrainOptions o;
  o.run_dir = dir;
  const std::string what = diverged([&] { Trainer(parse_train_config(text, "lr10.yaml"), o).run(); });
  std::cout << "[ message  ] " << what << "\n";
  ASSERT_FALSE(what.empty()) << "the run did not diverge";
  // Measured: a KL of 1.4e35 after the first minibatches.
  EXPECT_TRUE(contains(what, "iteration 1, epoch 1: the KL between the old and the new policy is ")) << what;
  EXPECT_TRUE(contains(what, ", above 100; stopping without saving (the last checkpoint is kept)")) << what;
  EXPECT_FALSE(std::filesystem::exists(dir / "checkpoint.pt"));
  EXPECT_TRUE(read_metrics_csv(dir / "metrics.csv").rows.empty());
}

// The KL bound alone: a batch whose old policy is 15 standard deviations from the network's (its
// actions at the old means, so that every ratio is 0 and every loss finite) is stopped by the KL.
TEST(Divergence, AKlPastItsBoundIsDivergenceEvenWhenEveryLossIsFinite) {
  TrainConfig c = parse_train_config("ppo: {epochs: 1, value_epochs: 1, minibatch: 4, kl_penalty: false}\n", "kl.yaml");
  PpoLearner learner(2, 1, c);
  PpoBatch b;
  b.input = torch::ones({4, 2});
  b.action = torch::full({4, 1}, 15.0);
  b.old_mean = torch::full({4, 1}, 15.0);
  b.old_log_std = torch::zeros({4, 1});
  b.advantage = torch::tensor({1.f, -1.f, 0.5f, 2.f});
  b.target = torch::zeros({4});
  b.old_value = torch::zeros({4});
  std::mt19937_64 rng(1);
  const std::string what = diverged([&] { learner.update(b, rng, false, 5); });
  EXPECT_TRUE(contains(what, "iteration 5, epoch 1: the KL between the old and the new policy is ")) << what;
  EXPECT_TRUE(contains(what, ", above 100;")) << what;
}

// A discriminator whose weights turn NaN, or explode while every reward stays finite (clipped):
// the iteration stops naming the reward source and the weight; the checkpoint of the iteration
// before stays, and the run resumes from it.
TEST(Divergence, ADiscriminatorThatDivergesStopsTheRunAndTheLastCheckpointResumes) {
  const auto dir = test::temp_dir("divergence_discriminator");
  write_demonstrations(dir / "expert.csv", test::oscillator_expert(4));
  const TrainConfig cfg = parse_train_config(test::gail_config(dir / "expert.csv", 10) + "checkpoint_every: 1\n", "osc.yaml");
  for (const double poison : {std::nan(""), 1e7}) {
    const auto run = dir / (std::isnan(poison) ? "nan" : "exploded");
    TrainOptions o = test::oscillator_options();
    o.run_dir = run;
    Trainer t(cfg, o);
    t.iterate();
    t.iterate();
    const std::string saved = read_text_file(run / "checkpoint.pt");
    auto& source = dynamic_cast<AdversarialRewardSource&>(*impl_of(t).rewards[0].second);
    {
      torch::NoGradGuard no_grad;
      source.discriminator().net()->parameters()[0].view(-1)[0] = poison;
    }
    const std::string what = diverged([&] { t.iterate(); });
    EXPECT_TRUE(contains(what, "iteration 3")) << what;
    EXPECT_TRUE(contains(what, "reward source 'gail'")) << what;
    EXPECT_TRUE(contains(what, std::isnan(poison) ? "non-finite reward" : "discriminator: parameter 'net.")) << what;
    if (!std::isnan(poison)) {
      EXPECT_TRUE(contains(what, "has exploded (a weight of 1e+07, above 1e+06)")) << what;
    }
    EXPECT_EQ(read_text_file(run / "checkpoint.pt"), saved);
    EXPECT_EQ(read_metrics_csv(run / "metrics.csv").rows.size(), 2u);
    // Saving that state is refused too.
    EXPECT_THROW(t.save_checkpoint(run / "poisoned.pt"), TrainingDiverged);
    EXPECT_FALSE(std::filesystem::exists(run / "poisoned.pt"));
    TrainOptions again = test::oscillator_options();
    again.run_dir = run;
    again.resume = true;
    Trainer resumed(cfg, again);
    EXPECT_EQ(resumed.iteration(), 2);
    EXPECT_EQ(resumed.iterate().iteration, 3);
  }
}
