// Steering: its measurement (learn/imitation/steering_eval.hpp), the heading error pinned on
// hand-made travels and the trial loop's accounting and errors on the humanoid; and the runtime's
// command (Controller::set_heading, PlaySession::steer) reaching a steerable skill's input.
#include "learn/imitation/steering_eval.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/play_session.hpp"
#include "core/error.hpp"
#include "env/imitation_env.hpp"
#include "mimic/runtime.hpp"
#include "steered_skill.hpp"
#include "../humanoid_data.hpp"

using namespace mimic;

TEST(HeadingError, IsTheAngleBetweenTheTravelAndTheCommand) {
  EXPECT_NEAR(heading_error_degrees(Vec3(1, 0, 0), 0.0), 0.0, 1e-12);
  EXPECT_NEAR(heading_error_degrees(Vec3(1, 1, 0), 0.0), 45.0, 1e-12);
  EXPECT_NEAR(heading_error_degrees(Vec3(1, -1, 0), 0.0), 45.0, 1e-12);
  EXPECT_NEAR(heading_error_degrees(Vec3(-1, 0, 3), 0.0), 180.0, 1e-12);  // height ignored
  EXPECT_NEAR(heading_error_degrees(Vec3(0, 2, 0), -kPi / 2), 180.0, 1e-12);
  // Across the +-180 degree seam: travelling at 170 degrees, commanded -170: 20 apart.
  EXPECT_NEAR(heading_error_degrees(Vec3(std::cos(deg_to_rad(170)), std::sin(deg_to_rad(170)), 0), deg_to_rad(-170)), 20.0, 1e-9);
  // A command given unwrapped (350 degrees is -10).
  EXPECT_NEAR(heading_error_degrees(Vec3(1, 0, 0), deg_to_rad(350)), 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(heading_error_degrees(Vec3(0, 0, 1), 0.0), 180.0);  // no horizontal travel
}

namespace {

ImitationEnvConfig steered(double max_seconds) {
  ImitationEnvConfig cfg;
  cfg.init = ImitationEnvConfig::Init::FixedPose;
  cfg.goal = ImitationEnvConfig::Goal::Heading;
  cfg.goal_period = 1e6;
  cfg.env.max_seconds = max_seconds;
  return cfg;
}

}  // namespace

TEST(SteeringEval, CountsEveryTrialAsAFallOrAReadingAndNamesItsErrors) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  auto env = make_imitation_env(ch, nullptr, steered(10.0));
  // Limp (every PD target at +1 rad): the character folds and goes down in every trial.
  const PolicyFunction limp = [&](const Eigen::VectorXd&) { return Eigen::VectorXd::Constant(env->action_size(), 1.0); };
  SteeringOptions o;
  o.trials = 3;
  o.hold_seconds = 2.0;
  const SteeringReport r = measure_steering(*env, limp, 1, o);
  EXPECT_EQ(r.trials, 3);
  EXPECT_EQ(r.falls, 3);
  EXPECT_TRUE(r.error_degrees.empty());
  EXPECT_DOUBLE_EQ(r.success_rate(), 0.0);  // a fall is a miss
  EXPECT_DOUBLE_EQ(r.respond_seconds, 2.0);
  // Episodes shorter than a trial are named, not read as short trials.
  auto brief = make_imitation_env(ch, nullptr, steered(1.0));
  const PolicyFunction still = [&](const Eigen::VectorXd&) { return Eigen::VectorXd::Zero(brief->action_size()); };
  try {
    (void)measure_steering(*brief, still, 1, o);
    ADD_FAILURE() << "a 1 s episode passed for a 4 s trial";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("give the environment longer episodes"), std::string::npos) << e.what();
  }
  // No heading goal, or options out of range.
  ImitationEnvConfig plain;
  plain.init = ImitationEnvConfig::Init::FixedPose;
  auto no_goal = make_imitation_env(ch, nullptr, plain);
  EXPECT_THROW((void)measure_steering(*no_goal, limp, 1, o), Error);
  o.turn_degrees = 200;
  EXPECT_THROW((void)measure_steering(*env, limp, 1, o), Error);
  o.turn_degrees = 90, o.respond_seconds = 3.0;  // after the 2 s hold
  EXPECT_THROW((void)measure_steering(*env, limp, 1, o), Error);
}


TEST(SteeringRuntime, ACommandedHeadingIsWhatASteerableSkillObserves) {
  MIMIC_NEED_HUMANOID();
  const auto steered = test::steered_skill(true, "steered");
  const auto plain = test::steered_skill(false, "plain");
  Controller c({steered, plain});
  EXPECT_TRUE(c.steerable("steered"));
  EXPECT_FALSE(c.steerable("plain"));
  EXPECT_THROW((void)c.steerable("nobody"), Error);
  EXPECT_TRUE(std::isnan(c.heading()));
  EXPECT_THROW(c.set_heading(std::nan("")), Error);
  const int frame = steered->frame_size();
  // The goal's cos and sin close the newest frame of the input the step acted on.
  const auto goal_seen = [&] {
    const Eigen::VectorXd& in = c.last_input();
    return Eigen::Vector2d(in[in.size() - 2], in[in.size() - 1]);
  };
  c.step();
  const double facing = c.facing();
  c.set_heading(facing + kPi / 2);  // a quarter turn to the left
  c.step();
  EXPECT_NEAR(c.heading(), std::remainder(facing + kPi / 2, 2 * kPi), 1e-12);
  // Observed from where the character faced before the step (the frame was observed then).
  EXPECT_NEAR(goal_seen().x(), std::cos(kPi / 2), 1e-6);
  EXPECT_NEAR(goal_seen().y(), std::sin(kPi / 2), 1e-6);
  // Held step after step, against the environment's own redraws (every 4 s).
  for (int t = 0; t < 150; ++t)
    if (c.step().episode_over) c.reset();  // (the untrained skill falls; a new start keeps the command)
  const double relative = c.heading() - c.facing();
  c.step();
  EXPECT_NEAR(goal_seen().x(), std::cos(relative), 1e-6);
  EXPECT_NEAR(goal_seen().y(), std::sin(relative), 1e-6);
  EXPECT_EQ(c.last_input().size(), frame * steered->history());
  // A skill without the goal acts as before: its input has no goal part to set.
  c.switch_to("plain");
  c.step();
  EXPECT_EQ(c.last_input().size(), plain->input_size());
}

TEST(SteeringRuntime, APlaySessionSteersFromTheCharactersFacingThenFromItsLastCommand) {
  MIMIC_NEED_HUMANOID();
  const auto steered = test::steered_skill(true, "steered");
  PlaySession session({steered}, PlayOptions{});
  const double facing = session.controller().facing();
  ASSERT_TRUE(session.steer(30.0));
  EXPECT_NEAR(session.controller().heading(), std::remainder(facing + deg_to_rad(30), 2 * kPi), 1e-12);
  session.step();
  ASSERT_TRUE(session.steer(-90.0));
  EXPECT_NEAR(session.controller().heading(), std::remainder(facing - deg_to_rad(60), 2 * kPi), 1e-12);
  EXPECT_EQ(session.events().back().event, "steer");
  // Where no skill takes a heading, nothing is commanded (the window turns its camera instead).
  PlaySession plain({test::steered_skill(false, "plain")}, PlayOptions{});
  EXPECT_FALSE(plain.steer(30.0));
  EXPECT_TRUE(std::isnan(plain.controller().heading()));
}
