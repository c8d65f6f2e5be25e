// Crossing a course (learn/imitation/crossing_eval.hpp): one trial's bookkeeping pinned on
// hand-made steps, and the trial loop's accounting and errors on the humanoid over stairs.
#include "learn/imitation/crossing_eval.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "env/imitation_env.hpp"
#include "../humanoid_data.hpp"

using namespace mimic;

TEST(CrossingTrial, CrossesAtTheFinishUnlessDownFirst) {
  // Standing height 1: lying is below 0.5 for 10 steps in a row (the robustness protocol's rule).
  CrossingTrial walk(3.0, 1.0);
  EXPECT_FALSE(walk.update(1.0, 0.9, false));
  EXPECT_FALSE(walk.update(2.99, 0.4, false));  // low for one step: a stumble, not down
  EXPECT_TRUE(walk.update(3.0, 0.9, false));    // at the finish line
  EXPECT_TRUE(walk.crossed());
  EXPECT_FALSE(walk.down());
  EXPECT_EQ(walk.steps(), 3);
  EXPECT_TRUE(walk.update(-5.0, 0.0, true));  // decided: later steps change nothing
  EXPECT_EQ(walk.steps(), 3);
  EXPECT_DOUBLE_EQ(walk.farthest_x(), 3.0);

  // Lying 10 steps in a row before the finish: down at the tenth, even past the line after.
  CrossingTrial fall(3.0, 1.0);
  for (int t = 1; t <= 9; ++t) EXPECT_FALSE(fall.update(2.0 + 0.01 * t, 0.3, false)) << t;
  EXPECT_TRUE(fall.update(2.1, 0.3, false));
  EXPECT_TRUE(fall.down());
  EXPECT_FALSE(fall.crossed());
  fall.update(4.0, 1.0, false);
  EXPECT_FALSE(fall.crossed());
  EXPECT_DOUBLE_EQ(fall.farthest_x(), 2.1);

  // A crouch (0.6 of standing) on its feet is not down; a body on the ground for 10 steps is.
  CrossingTrial crouch(3.0, 1.0);
  for (int t = 0; t < 30; ++t) EXPECT_FALSE(crouch.update(0.0, 0.6, false));
  CrossingTrial contact(3.0, 1.0);
  for (int t = 0; t < 9; ++t) EXPECT_FALSE(contact.update(0.0, 0.9, true));
  EXPECT_TRUE(contact.update(0.0, 0.9, true));
  EXPECT_TRUE(contact.down());

  // An episode the environment ended as a failure is down at once.
  CrossingTrial failed(3.0, 1.0);
  EXPECT_TRUE(failed.update(0.5, 0.9, false, /*failed=*/true));
  EXPECT_TRUE(failed.down());
}

namespace {

ImitationEnvConfig on(TerrainKind kind, double max_seconds) {
  ImitationEnvConfig cfg;
  cfg.init = ImitationEnvConfig::Init::FixedPose;
  cfg.env.terrain.kind = kind;
  cfg.env.max_seconds = max_seconds;
  return cfg;
}

}  // namespace

TEST(CrossingEval, CountsEveryTrialAndNamesItsErrors) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  auto stairs = make_imitation_env(ch, nullptr, on(TerrainKind::Stairs, 10.0));
  // Limp (every PD target at +1 rad): the character folds at the start and is down in every trial.
  const PolicyFunction limp = [&](const Eigen::VectorXd&) { return Eigen::VectorXd::Constant(stairs->action_size(), 1.0); };
  CrossingOptions o;
  o.trials = 3;
  o.seconds = 3.0;
  const CrossingReport r = measure_crossing(*stairs, limp, 1, o);
  EXPECT_EQ(r.trials, 3);
  EXPECT_EQ(r.falls, 3);
  EXPECT_EQ(r.crossed, 0);
  EXPECT_DOUBLE_EQ(r.success_rate(), 0.0);
  EXPECT_NEAR(r.finish_x, 8.5 + 0.5, 1e-12);  // the default stairs end at 8.5 m (Terrain.CourseEndIsWhereTheLastFeatureEnds)
  ASSERT_EQ(r.progress.size(), 3u);
  for (double p : r.progress) EXPECT_LT(p, 0.2);  // it folded near the origin
  EXPECT_DOUBLE_EQ(r.seconds, 3.0);
  // Episodes shorter than a trial are named, not read as short trials.
  auto brief = make_imitation_env(ch, nullptr, on(TerrainKind::Stairs, 1.0));
  const PolicyFunction still = [&](const Eigen::VectorXd&) { return Eigen::VectorXd::Zero(brief->action_size()); };
  try {
    (void)measure_crossing(*brief, still, 1, o);
    ADD_FAILURE() << "a 1 s episode passed for a 3 s trial";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("give the environment longer episodes"), std::string::npos) << e.what();
  }
  // Flat ground has no course; options out of range.
  auto flat = make_imitation_env(ch, nullptr, on(TerrainKind::Flat, 10.0));
  EXPECT_THROW((void)measure_crossing(*flat, limp, 1, o), Error);
  o.seconds = 0;
  EXPECT_THROW((void)measure_crossing(*stairs, limp, 1, o), Error);
}
