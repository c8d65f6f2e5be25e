// The imitation environment: seed 000's "move forward" task's reward terms against hand-computed
// values, the heading and steering goals, courses, fallen starts, projectiles. Its starts are in
// imitation_env_starts_test.cpp; how its episodes end and its config keys in
// imitation_env_episodes_test.cpp.
#include "env/imitation_env.hpp"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "core/yaml_reader.hpp"
#include "env/context_env.hpp"
#include "env/env_factory.hpp"
#include "motion/deepmimic.hpp"
#include "humanoid_data.hpp"
#include "imitation_env_helpers.hpp"

using namespace mimic;
using namespace mimic::test;

TEST(ImitationEnv, RewardTermsMatchHandComputedValues) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init = Init::FixedPose;
  cfg.alive_bonus = 2.0;
  cfg.forward_weight = 0.5;
  cfg.lateral_weight = 0.3;
  cfg.control_weight = 0.01;
  auto env = make_imitation_env(ch, nullptr, cfg);
  const double dt = 1.0 / 30.0;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env->action_size());

  // No contact and no joint motion in one step: the root moves exactly at its velocity.
  env->reset(flying(ch));
  StepResult r = env->step(zero);
  ASSERT_EQ(r.reward_terms.size(), 4u);
  EXPECT_EQ(r.reward_terms[0].first, "alive");
  EXPECT_EQ(r.reward_terms[1].first, "forward");
  EXPECT_EQ(r.reward_terms[2].first, "lateral");
  EXPECT_EQ(r.reward_terms[3].first, "control");
  EXPECT_EQ(r.termination, Termination::None);
  EXPECT_DOUBLE_EQ(term(r, "alive"), 2.0);
  EXPECT_NEAR(term(r, "forward"), 0.5 * 2.0, 1e-9);
  EXPECT_NEAR(term(r, "lateral"), -0.3 * (0.4 + 0.5 * dt), 1e-9);
  EXPECT_DOUBLE_EQ(term(r, "control"), 0.0);
  EXPECT_NEAR(r.reward(), 2.0 + 1.0 - 0.3 * (0.4 + 0.5 * dt), 1e-9);

  // Control: the action as the environment reads it, clipped to +-pi with NaN as 0.
  Eigen::VectorXd a = zero;
  a[0] = 0.5;
  a[1] = -1.0;
  a[5] = 10.0;
  a[9] = std::nan("");
  env->reset(flying(ch));
  r = env->step(a);
  EXPECT_NEAR(term(r, "control"), -0.01 * (0.25 + 1.0 + kPi * kPi), 1e-12);
  EXPECT_DOUBLE_EQ(term(r, "alive"), 2.0);

  // The target-speed variant: -w |v_x - target|.
  cfg.target_speed = 3.0;
  auto target = make_imitation_env(ch, nullptr, cfg);
  target->reset(flying(ch));
  EXPECT_NEAR(term(target->step(zero), "forward"), -0.5 * std::abs(2.0 - 3.0), 1e-9);
}

namespace {

// Standing starts with a target heading.
ImitationEnvConfig heading_goal() {
  ImitationEnvConfig cfg;
  cfg.init = Init::FixedPose;
  cfg.goal = ImitationEnvConfig::Goal::Heading;
  return cfg;
}

}  // namespace

TEST(ImitationEnv, AHeadingGoalRewardsSpeedAlongTheTargetAndIsObserved) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg = heading_goal();
  cfg.goal_speed = 1.0;
  cfg.goal_weight = 2.0;
  cfg.control_weight = 0.0;
  auto env = make_imitation_env(ch, nullptr, cfg);
  const auto layout = env->observation_layout();
  ASSERT_EQ(layout.back().name, "goal");
  ASSERT_EQ(layout.back().size, 2);
  ASSERT_EQ(layout.back().offset + 2, env->observation_size());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env->action_size());
  // Flying at (2, 0.5) m/s, facing +X: towards +Y the speed along the target is 0.5, a miss of
  // 0.5, the speed across it 2; facing across it earns nothing of the facing share.
  env->reset(flying(ch));
  set_goal_heading(*env, kPi / 2);
  StepResult r = env->step(zero);
  ASSERT_EQ(r.reward_terms.size(), 3u);  // alive, goal, control: the track's terms give way
  EXPECT_EQ(r.reward_terms[1].first, "goal");
  EXPECT_NEAR(term(r, "goal"), 2.0 * 0.7 * std::exp(-2.5 * (0.5 * 0.5 + 0.1 * 2.0 * 2.0)), 1e-9);
  EXPECT_NEAR(r.observation[env->observation_size() - 2], 0.0, 1e-6);  // cos, sin of the target
  EXPECT_NEAR(r.observation[env->observation_size() - 1], 1.0, 1e-6);  // in the heading frame
  // Along +X: 2 m/s for a target of 1, faster than asked (no miss), 0.5 across; facing it.
  env->reset(flying(ch));
  set_goal_heading(*env, 0.0);
  EXPECT_NEAR(term(env->step(zero), "goal"), 2.0 * (0.7 * std::exp(-2.5 * 0.1 * 0.5 * 0.5) + 0.3), 1e-9);
  // Away from it (-X): moving away earns nothing, and neither does facing away.
  env->reset(flying(ch));
  set_goal_heading(*env, kPi);
  EXPECT_NEAR(term(env->step(zero), "goal"), 0.0, 1e-9);
  // Towards 45 degrees to the left: along (2 + 0.5) / sqrt 2, across (2 - 0.5) / sqrt 2; facing
  // cos 45; at a sharpness of 0.1 and half the reward for facing.
  cfg.goal_sharpness = 0.1, cfg.goal_facing = 0.5;
  env = make_imitation_env(ch, nullptr, cfg);
  env->reset(flying(ch));
  set_goal_heading(*env, kPi / 4);
  const double across = 1.5 / std::sqrt(2.0);
  EXPECT_NEAR(term(env->step(zero), "goal"), 2.0 * (0.5 * std::exp(-0.1 * 0.1 * across * across) + 0.5 * std::sqrt(0.5)), 1e-9);
  // Parts are named once and hold at least one value.
  const auto nothing = [](const CharacterEnv&, Eigen::Ref<Eigen::VectorXd>) {};
  EXPECT_THROW(env->add_observation_part("goal", 1, nothing), Error);
  EXPECT_THROW(env->add_observation_part("empty", 0, nothing), Error);
}

TEST(ImitationEnv, TheHeadingGoalIsRedrawnEveryPeriodAndAtEveryStart) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg = heading_goal();
  cfg.goal_period = 0.5;  // 15 control steps
  auto env = make_imitation_env(ch, nullptr, cfg);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env->action_size());
  std::mt19937_64 rng(4);
  env->reset(rng);
  const double first = goal_heading(*env);
  for (int t = 1; t < 15; ++t) {
    env->step(zero);
    EXPECT_EQ(goal_heading(*env), first) << t;
  }
  const StepResult r = env->step(zero);
  const double second = goal_heading(*env);
  EXPECT_NE(second, first);
  EXPECT_GE(second, -kPi);
  EXPECT_LT(second, kPi);
  // The step that draws the new target already shows it.
  const double relative = second - heading_angle(env->world().pose().rot[0]);
  EXPECT_NEAR(r.observation[env->observation_size() - 2], std::cos(relative), 1e-9);
  EXPECT_NEAR(r.observation[env->observation_size() - 1], std::sin(relative), 1e-9);
  // Each start draws one; the same draw gives the same target.
  env->reset(rng);
  EXPECT_NE(goal_heading(*env), second);
  std::mt19937_64 again(4);
  env->reset(again);
  EXPECT_EQ(goal_heading(*env), first);
  // Only this env has one; periods must be positive.
  ImitationEnvConfig plain_cfg;
  plain_cfg.init = Init::FixedPose;
  auto plain = make_imitation_env(ch, nullptr, plain_cfg);
  EXPECT_THROW(goal_heading(*plain), Error);
  cfg.goal_period = 0.0;
  EXPECT_THROW(make_imitation_env(ch, nullptr, cfg), Error);
}

TEST(ImitationEnv, ASteeringGoalTurnsByAtMostGoalTurnFromWhereTheCharacterFaces) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg = heading_goal();
  cfg.goal_turn = 30.0;
  cfg.goal_period = 0.1;  // 3 control steps
  auto env = make_imitation_env(ch, nullptr, cfg);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env->action_size());
  std::mt19937_64 rng(7);
  // A start facing 170 degrees: its targets lie within 30 degrees of it, across the +-180 seam.
  InitState start = flying(ch);
  start.pose.rot[0] = heading_rotation(170.0 * kPi / 180.0) * start.pose.rot[0];
  double lowest = 1e9, highest = -1e9;
  for (int episode = 0; episode < 40; ++episode) {
    env->reset(rng);
    const double facing = heading_angle(env->world().pose().rot[0]);
    const double turn = std::remainder(goal_heading(*env) - facing, 2 * kPi);
    EXPECT_LE(std::abs(turn), 30.0 * kPi / 180.0 + 1e-9) << episode;
    lowest = std::min(lowest, turn), highest = std::max(highest, turn);
  }
  EXPECT_LT(lowest, -20.0 * kPi / 180.0);  // both ways, most of the range
  EXPECT_GT(highest, 20.0 * kPi / 180.0);
  env->reset(start);
  for (int t = 1; t <= 3; ++t) env->step(zero);  // the period's draw
  const double facing = heading_angle(env->world().pose().rot[0]);
  const double target = goal_heading(*env);
  EXPECT_GE(target, -kPi);
  EXPECT_LT(target, kPi);
  EXPECT_LE(std::abs(std::remainder(target - facing, 2 * kPi)), 30.0 * kPi / 180.0 + 1e-9);
  // 0: straight on, where the character faces at the draw.
  cfg.goal_turn = 0.0;
  auto straight = make_imitation_env(ch, nullptr, cfg);
  std::mt19937_64 other(8);
  straight->reset(other);  // an episode whose target was +x
  // A start given as a state draws its own target at once (a measurement from a clip's phases
  // starts this way): straight on from 170 degrees, and its first observation shows it ahead.
  const Eigen::VectorXd first = straight->reset(start);
  EXPECT_NEAR(goal_heading(*straight), std::remainder(heading_angle(straight->world().pose().rot[0]), 2 * kPi), 1e-12);
  EXPECT_NEAR(std::abs(goal_heading(*straight)), 170.0 * kPi / 180.0, 0.05);
  EXPECT_NEAR(first[first.size() - 2], 1.0, 1e-12);
  EXPECT_NEAR(first[first.size() - 1], 0.0, 1e-12);
  for (int t = 1; t <= 3; ++t) straight->step(zero);
  EXPECT_NEAR(goal_heading(*straight), heading_angle(straight->world().pose().rot[0]), 1e-12);
  cfg.goal_turn = -1.0;
  EXPECT_THROW(make_imitation_env(ch, nullptr, cfg), Error);
  cfg.goal_turn = 181.0;
  EXPECT_THROW(make_imitation_env(ch, nullptr, cfg), Error);
}

TEST(ImitationEnv, ARedrawnWallsCourseIsNewAtEveryStart) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init = Init::FixedPose;
  cfg.env.terrain.kind = TerrainKind::Walls;
  cfg.env.terrain.redraw = true;
  auto env = make_imitation_env(ch, nullptr, cfg);
  const double x = cfg.env.terrain.start_zone + 0.1;  // inside the first wall
  // Which of 40 places across the first wall are open.
  const auto open = [&] {
    std::vector<bool> out;
    for (int i = 0; i < 40; ++i) out.push_back(env->terrain().height(x, -9.75 + 0.5 * i) == 0.0);
    return out;
  };
  std::mt19937_64 rng(5);
  env->reset(rng);
  const auto first = open();
  int changed = 0;
  for (int start = 0; start < 3; ++start) {
    env->reset(rng);
    if (open() != first) ++changed;
  }
  EXPECT_GE(changed, 2);
  EXPECT_EQ(std::count(first.begin(), first.end(), true), 4);  // a 2 m opening: 4 places 0.5 m apart
}

TEST(ImitationEnv, FallenStartsLieWhereTheyLandedAndTheirContactsEndNothing) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  ImitationEnvConfig cfg;
  cfg.fallen_starts = 1.0;
  auto env = make_imitation_env(ch, walk, cfg);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env->action_size());
  std::mt19937_64 rng(3);
  double lowest_forward = 1, highest_forward = -1;
  for (int i = 0; i < 12; ++i) {
    env->reset(rng);
    ASSERT_TRUE(env->lying_start());
    EXPECT_LT(env->world().root_position().z(), 0.5 * ch.rest_root_height()) << i;  // on the ground
    EXPECT_LT(env->world().velocity().root_lin.norm(), 0.5) << i;                  // and settled
    const double forward = (env->world().pose().rot[0] * Vec3::UnitX()).z();        // < 0: face down
    lowest_forward = std::min(lowest_forward, forward), highest_forward = std::max(highest_forward, forward);
    // Lying, its root and chest touch the ground: a fall for an ordinary start, not for this one.
    for (int t = 0; t < 5; ++t) EXPECT_NE(env->step(zero).termination, Termination::Fall) << i;
  }
  EXPECT_LT(lowest_forward, -0.3);  // face down and face up both
  EXPECT_GT(highest_forward, 0.3);
  // Its time limit still ends it (a looping clip's: max_seconds, 10 s), as a truncation.
  Termination end = Termination::None;
  for (int steps = 0; end == Termination::None && steps < 1000; ++steps) end = env->step(zero).termination;
  EXPECT_EQ(end, Termination::TimeLimit);
  EXPECT_NEAR(env->elapsed(), 10.0, 0.05);
  // A start given as a state afterwards is an ordinary one: lying, its contacts end it.
  env->reset(env->state_on_clip(*walk, 0.0));
  EXPECT_FALSE(env->lying_start());
  // Off (the default), the starts are the ones drawn without the key.
  ImitationEnvConfig plain;
  auto a = make_imitation_env(ch, walk, plain);
  plain.fallen_starts = 0.0;
  auto b = make_imitation_env(ch, walk, plain);
  std::mt19937_64 r1(9), r2(9);
  EXPECT_TRUE(a->reset(r1).isApprox(b->reset(r2)));
  EXPECT_FALSE(a->lying_start());
  cfg.fallen_starts = 1.5;
  EXPECT_THROW(make_imitation_env(ch, walk, cfg), Error);
}

TEST(ImitationEnv, FallenStartsOfAGetUpLieOnItsClipsSideAndLastOneAndAHalfClips) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  for (const char* name : {"humanoid3d_getup_facedown.txt", "humanoid3d_getup_faceup.txt"}) {
    const auto getup = test::humanoid3d_motion(ch, name);
    ASSERT_TRUE(begins_lying(*getup)) << name;
    const int side = lying_side(getup->frames.front());
    ASSERT_NE(side, 0) << name;
    ImitationEnvConfig cfg;
    cfg.fallen_starts = 1.0;
    auto env = make_imitation_env(ch, getup, cfg);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env->action_size());
    std::mt19937_64 rng(5);
    int on_side = 0;
    const int starts = 10;
    for (int i = 0; i < starts; ++i) {
      env->reset(rng);
      ASSERT_TRUE(env->lying_start());
      on_side += side * (env->world().pose().rot[0] * Vec3::UnitX()).z() > 0;
    }
    // Dropped from the clip's side, a body may roll on landing; most stay (random sides: half).
    EXPECT_GE(on_side, 8) << name;
    // The last episode, limp, ends with its clip's time: 1.5 durations, not max_seconds (10 s).
    Termination end = Termination::None;
    for (int steps = 0; end == Termination::None && steps < 1000; ++steps) end = env->step(zero).termination;
    EXPECT_EQ(end, Termination::ClipEnd) << name;
    EXPECT_NEAR(env->elapsed(), 1.5 * getup->duration(), 0.05) << name;  // within a control step (1/30 s)
  }
}

TEST(ImitationEnv, BuildsAProprioceptiveEnvWithoutAReference) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  auto env =
      make_imitation_env(ch, test::humanoid3d_motion(ch, "humanoid3d_kick.txt"), ImitationEnvConfig{});
  EXPECT_EQ(env->reference(), nullptr);  // a non-cyclic clip cannot end episodes (no ClipEnd)
  EXPECT_EQ(env->action_size(), 28);
  ASSERT_EQ(env->observation_layout().size(), 2u);
  EXPECT_EQ(env->observation_layout()[0].name, "full_state");
  EXPECT_EQ(env->observation_layout()[1].name, "egocentric");
  EXPECT_EQ(env->config().max_seconds, 10.0);

  ImitationEnvConfig cfg;
  EXPECT_THROW(make_imitation_env(ch, nullptr, cfg), Error);  // Mocap needs a clip
  cfg.init = Init::FixedPose;
  EXPECT_NO_THROW(make_imitation_env(ch, nullptr, cfg));
  cfg.lateral_weight = -0.1;
  EXPECT_THROW(make_imitation_env(ch, nullptr, cfg), Error);
  cfg.lateral_weight = 0.1;
  cfg.init_noise = std::nan("");
  EXPECT_THROW(make_imitation_env(ch, nullptr, cfg), Error);
}

// mimic eval --robustness rebuilds a run's env with projectiles: a GAIL or ICCGAN run on this
// task must accept them.
TEST(ImitationEnv, LaunchesProjectilesWhenTheConfigAsks) {
  MIMIC_NEED_HUMANOID();
  const YamlReader reader("test.yaml");
  const EnvFactory f = make_env_factory(reader.parse("{name: imitation, init: fixed, projectiles: {enabled: true, mass: 5}}", "bad"), reader);
  auto env = f();
  auto* character = dynamic_cast<CharacterEnv*>(env.get());
  ASSERT_NE(character, nullptr);
  ASSERT_NE(character->projectiles(), nullptr);
  std::mt19937_64 rng(1);
  env->reset(rng);
  for (int t = 0; t < 3; ++t) env->step(Eigen::VectorXd::Zero(env->action_size()));
  EXPECT_EQ(character->projectiles()->stats().launched, 3);  // one per control step
}
