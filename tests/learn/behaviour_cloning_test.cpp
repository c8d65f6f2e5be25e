// Behavioural cloning (seed 002's baseline): the normaliser takes the demonstrations' statistics,
// the policy mean regresses their actions, and the result acts as the expert did.
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "learn/trainer/trainer_impl.hpp"
#include "imitation_fixtures.hpp"
#include "../error_message.hpp"
#include "trainer_access.hpp"

using namespace mimic;
using mimic::test::error_of;

namespace {

TrainConfig oscillator_config(const std::string& networks = "policy: {hidden: [32, 32]}\nvalue: {hidden: [8]}\n") {
  return parse_train_config("seed: 4\ncollect: {envs: 2, threads: 1, samples: 64}\n" + networks, "clone.yaml");
}

}  // namespace

// The oscillator's expert pushes with force -x: the clone learns that map from 20 episodes.
TEST(BehaviourCloning, TheClonedPolicyActsAsTheExpertAndItsNormaliserIsTheDemonstrations) {
  const Demonstrations d = test::oscillator_expert(20);
  Trainer t(oscillator_config(), test::oscillator_options());
  auto error_on = [&](const Demonstrations& demos) {
    double sum = 0;
    for (int i = 0; i < demos.size(); ++i) sum += (test::act(t, demos.obs.row(i).transpose()) - demos.action.row(i).transpose()).squaredNorm();
    return sum / demos.size();
  };
  const double before = error_on(d);
  const double loss = t.clone_behaviour(d, 60, 3e-3, 64, 7);
  const double after = error_on(d);
  std::cout << "[ figures  ] mean squared action error " << before << " -> " << after << " (final training loss " << loss << ")\n";
  EXPECT_LT(after, 0.02 * before);
  EXPECT_NEAR(loss, after, 0.5 * after + 1e-4);  // the loss it reports is the error it reaches
  // The normaliser holds the demonstrations' mean and variance, nothing of before.
  const Eigen::VectorXd mean = d.obs.colwise().mean().transpose();
  EXPECT_TRUE(impl_of(t).obs_norm.mean().isApprox(mean, 1e-9)) << impl_of(t).obs_norm.mean().transpose() << " vs " << mean.transpose();
  EXPECT_DOUBLE_EQ(impl_of(t).obs_norm.count(), static_cast<double>(d.size()));
  // On states the expert never met (a larger orbit) the clone still pushes back towards 0.
  Demonstrations far = d;
  far.obs *= 1.5, far.action *= 1.5;
  EXPECT_LT(error_on(far), 0.1 * before * 2.25);
  // The same seed clones the same policy.
  Trainer again(oscillator_config(), test::oscillator_options());
  EXPECT_DOUBLE_EQ(again.clone_behaviour(d, 60, 3e-3, 64, 7), loss);
}

TEST(BehaviourCloning, DemonstrationsThatDoNotFitOrSettingsThatCannotWorkAreErrors) {
  Demonstrations d = test::oscillator_expert(2);
  d.source = "demos.csv";
  Trainer t(oscillator_config(), test::oscillator_options());
  Demonstrations wide = d;
  wide.obs.conservativeResize(Eigen::NoChange, 3);
  EXPECT_NE(error_of([&] { t.clone_behaviour(wide, 1, 1e-3, 8, 1); }).find("demos.csv: demonstrations have 3 observation and 1 action values; the policy takes 2"),
            std::string::npos);
  EXPECT_NE(error_of([&] { t.clone_behaviour(d, 0, 1e-3, 8, 1); }).find("epochs, batch and learning rate must be positive"), std::string::npos);
  EXPECT_NE(error_of([&] { t.clone_behaviour(d, 1, 0.0, 8, 1); }).find("must be positive"), std::string::npos);
  Trainer stacked(oscillator_config("policy: {hidden: [8], history: 2}\nvalue: {hidden: [8], history: 2}\n"), test::oscillator_options());
  EXPECT_NE(error_of([&] { stacked.clone_behaviour(d, 1, 1e-3, 8, 1); }).find("needs a policy that sees one frame"), std::string::npos);
}
