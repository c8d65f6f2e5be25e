// The imitation environment: seed 000's "move forward" task's reward terms against hand-computed
// values, the two kinds of episode start, how episodes end, and the character keys of a config.
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

using namespace mimic;

namespace {

using Init = ImitationEnvConfig::Init;

// The clip turned by `yaw` about +Z and moved by `shift`: a start away from the track's.
std::shared_ptr<const Clip> moved(const Clip& clip, double yaw, const Vec3& shift) {
  Clip out = clip;
  const Quat r = heading_rotation(yaw);
  for (Pose& p : out.frames) {
    p.root_pos = r * p.root_pos + shift;
    p.rot[0] = r * p.rot[0];
  }
  return std::make_shared<const Clip>(std::move(out));
}

double term(const StepResult& r, const std::string& name) {
  for (const auto& [n, v] : r.reward_terms)
    if (n == name) return v;
  throw std::logic_error("no reward term " + name);
}

double max_joint_difference(const Pose& a, const Pose& b) {
  double d = 0;
  for (std::size_t j = 1; j < a.rot.size(); ++j)
    d = std::max(d, rotation_distance(a.rot[j], b.rot[j]));
  return d;
}

// The character up in the air, rigid (PD targets = its pose), flying along +X and sideways.
InitState flying(const CharacterModel& ch) {
  InitState s{rest_pose(ch.skeleton, Vec3(0, 0.4, 5.0)), PoseVelocity{}, 0.0, {}};
  s.velocity.root_lin = Vec3(2.0, 0.5, 0.0);
  s.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
  return s;
}

// The error making an env factory from `env_yaml` gives, or "no error".
std::string factory_error(const YamlReader& r, const std::string& env_yaml) {
  try {
    (void)make_env_factory(r.parse(env_yaml, ""), r);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

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

TEST(ImitationEnv, PlacingAtTheTrackStartKeepsTheMotion) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  const auto turned = moved(*walk, 2.0, Vec3(5, -3, 0));
  const InitState a = place_at_track_start(init_state_from_clip(*walk, 0.4));
  const InitState b = place_at_track_start(init_state_from_clip(*turned, 0.4));
  for (const InitState* s : {&a, &b}) {
    EXPECT_NEAR(s->pose.root_pos.x(), 0.0, 1e-12);
    EXPECT_NEAR(s->pose.root_pos.y(), 0.0, 1e-12);
    EXPECT_NEAR(heading_angle(s->pose.rot[0]), 0.0, 1e-9);
  }
  EXPECT_NEAR(b.pose.root_pos.z(), walk->sample(0.4).root_pos.z(), 1e-9);
  // The same state wherever the clip was: the turn is undone for pose and velocities alike.
  EXPECT_LT(rotation_distance(a.pose.rot[0], b.pose.rot[0]), 1e-9);
  EXPECT_LT(max_joint_difference(a.pose, b.pose), 1e-9);
  EXPECT_TRUE(a.velocity.root_lin.isApprox(b.velocity.root_lin, 1e-9));
  EXPECT_TRUE(a.velocity.root_ang.isApprox(b.velocity.root_ang, 1e-9));
  EXPECT_GT(a.velocity.root_lin.x(), 0.5);  // walking forward, i.e. along +X
}

TEST(ImitationEnv, MocapStartsDifferAndFaceAlongTheTrack) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  // A clip facing elsewhere and away from the origin: starts must still be at the track's start.
  const auto walk = moved(*test::humanoid3d_motion(ch, "humanoid3d_walk.txt"), -2.5, Vec3(-4, 7, 0));
  auto env = make_imitation_env(ch, walk, ImitationEnvConfig{});
  std::vector<Pose> starts;
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    std::mt19937_64 rng(seed);
    env->reset(rng);
    const Pose p = env->world().pose();
    EXPECT_NEAR(p.root_pos.x(), 0.0, 1e-9);
    EXPECT_NEAR(p.root_pos.y(), 0.0, 1e-9);
    EXPECT_GT(p.root_pos.z(), 0.7);
    EXPECT_NEAR(heading_angle(p.rot[0]), 0.0, 1e-6);
    EXPECT_GT(env->world().data()->qvel[0], 0.5)
        << "seed " << seed;  // the clip's walking speed, along +X
    starts.push_back(p);
  }
  EXPECT_GT(max_joint_difference(starts[0], starts[1]), 0.1);
  EXPECT_GT(max_joint_difference(starts[1], starts[2]), 0.1);
  // The same draw gives the same start.
  std::mt19937_64 rng(2);
  env->reset(rng);
  EXPECT_LT(max_joint_difference(env->world().pose(), starts[1]), 1e-12);
}

// Seed 004's integrated learning: starts from every clip of a collection, each in proportion to
// its duration (a pose drawn uniformly from all their frames).
namespace {

// A clip holding the rest pose with the right elbow bent `angle` rad for `seconds`: starts from
// different clips are told apart by the elbow.
std::shared_ptr<const Clip> held_elbow(const CharacterModel& ch, double angle, double seconds) {
  const auto elbow = static_cast<std::size_t>(ch.skeleton.find("right_elbow"));
  Clip c;
  c.name = "held_" + std::to_string(angle);
  c.skeleton = ch.skeleton;
  Pose p = rest_pose(ch.skeleton, Vec3(0, 0, ch.rest_root_height() + 0.01));
  p.rot[elbow] = Quat(Eigen::AngleAxisd(angle, ch.skeleton.joints[elbow].axis));
  c.frames.assign(static_cast<std::size_t>(seconds * c.fps) + 1, p);
  return std::make_shared<const Clip>(std::move(c));
}

double elbow_angle(const CharacterEnv& env) {
  const Skeleton& sk = env.world().character().skeleton;
  const auto elbow = static_cast<std::size_t>(sk.find("right_elbow"));
  return revolute_angle(sk.joints[elbow], env.world().pose().rot[elbow]);
}

// Starts (of 400, seeded `seed`) whose right elbow is at 1.2 rad, after checking that every one
// is at 1.2 or 0.3 rad (from one of the two held poses).
int starts_at_1_2_of_400(CharacterEnv& env, unsigned seed) {
  std::mt19937_64 rng(seed);
  int high = 0, low = 0;
  for (int i = 0; i < 400; ++i) {
    env.reset(rng);
    const double angle = elbow_angle(env);
    if (std::abs(angle - 1.2) < 1e-6) ++high;
    if (std::abs(angle - 0.3) < 1e-6) ++low;
  }
  EXPECT_EQ(high + low, 400);
  return high;
}

}  // namespace

TEST(ImitationEnv, StartsFromSeveralClipsInProportionToTheirDurations) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ASSERT_GE(ch.skeleton.find("right_elbow"), 0);
  // Two held poses told apart by the right elbow: 1 s at 0.3 rad, 3 s at 1.2 rad.
  auto held = [&](double angle, double seconds) { return held_elbow(ch, angle, seconds); };
  ImitationEnvConfig cfg;
  cfg.init_noise = 0.0;
  auto env = make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{held(0.3, 1.0), held(1.2, 3.0)}, cfg);
  EXPECT_EQ(env->start_groups(), 2);
  EXPECT_NEAR(starts_at_1_2_of_400(*env, 5) / 400.0, 0.75, 0.06);  // 3 s of 4; binomial sd 0.022
  // Every clip must fit; an empty collection cannot start Mocap episodes.
  EXPECT_THROW(make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{}, cfg), Error);
  Clip other = *held(0.3, 1.0);
  other.skeleton.joints.pop_back();
  for (Pose& p : other.frames) p.rot.pop_back();
  EXPECT_THROW(make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{held(0.3, 1.0), std::make_shared<const Clip>(other)}, cfg),
               Error);
}

// A chosen start group (a clip of the list) restricts the starts to that clip until chosen again.
TEST(ImitationEnv, AChosenStartGroupStartsFromThatClipAlone) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init_noise = 0.0;
  auto env = make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{held_elbow(ch, 0.3, 1.0), held_elbow(ch, 1.2, 3.0)}, cfg);
  std::mt19937_64 rng(3);
  env->choose_start_group(0);  // the short clip, a quarter of the starts when drawn from both
  for (int i = 0; i < 40; ++i) {
    env->reset(rng);
    EXPECT_NEAR(elbow_angle(*env), 0.3, 1e-6) << "start " << i;
  }
  env->choose_start_group(1);
  for (int i = 0; i < 10; ++i) {
    env->reset(rng);
    EXPECT_NEAR(elbow_angle(*env), 1.2, 1e-6) << "start " << i;
  }
  EXPECT_EQ(env->start_group(), 1);
  EXPECT_THROW(env->choose_start_group(2), Error);
  EXPECT_THROW(env->choose_start_group(-2), Error);
  env->choose_start_group(-1);  // every clip again
  EXPECT_EQ(env->start_group(), -1);
}

// A behaviour context with starts: by_context starts each episode from its context's clip, also
// when the context is held; the config refuses it where the clips do not match the contexts.
TEST(ImitationEnv, ContextStartsComeFromTheContextsClip) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init_noise = 0.0;
  auto clips = [&] { return std::vector<std::shared_ptr<const Clip>>{held_elbow(ch, 0.3, 1.0), held_elbow(ch, 1.2, 3.0)}; };
  ContextEnv env(make_imitation_env(ch, clips(), cfg), 2, 0, true);
  const auto& character = dynamic_cast<const CharacterEnv&>(env.inner());
  std::mt19937_64 rng(11);
  int per_context[2] = {0, 0};
  for (int i = 0; i < 100; ++i) {
    env.reset(rng);
    const double expected = env.context() == 0 ? 0.3 : 1.2;
    EXPECT_NEAR(elbow_angle(character), expected, 1e-6) << "start " << i << ", context " << env.context();
    ++per_context[env.context()];
  }
  EXPECT_GT(per_context[0], 30);  // contexts drawn evenly, not by clip duration (binomial sd 5)
  EXPECT_GT(per_context[1], 30);
  env.hold_context(0);
  for (int i = 0; i < 10; ++i) {
    env.reset(rng);
    EXPECT_NEAR(elbow_angle(character), 0.3, 1e-6) << "held start " << i;
  }
  // Without the option the starts ignore the context (in proportion to the clips' durations).
  ContextEnv any(make_imitation_env(ch, clips(), cfg), 2, 0);
  int mismatched = 0;
  for (int i = 0; i < 100; ++i) {
    any.reset(rng);
    const double expected = any.context() == 0 ? 0.3 : 1.2;
    if (std::abs(elbow_angle(dynamic_cast<const CharacterEnv&>(any.inner())) - expected) > 1e-6) ++mismatched;
  }
  EXPECT_GT(mismatched, 20);
  // One clip per context, on a character env.
  EXPECT_THROW(ContextEnv(make_imitation_env(ch, clips(), cfg), 3, 0, true), Error);
  EXPECT_THROW(ContextEnv(std::make_unique<CharacterEnv>(ch, CharacterEnvConfig{}), 2, 0, true), Error);

  const YamlReader r("ctx.yaml");
  auto error = [&](const std::string& env_yaml) { return factory_error(r, env_yaml); };
  EXPECT_EQ(error("{name: imitation, clip: [deepmimic/motions/humanoid3d_walk.txt, deepmimic/motions/humanoid3d_run.txt], "
                  "context: {count: 2, period: 150, starts: by_context}}"),
            "no error");
  EXPECT_NE(error("{name: imitation, clip: deepmimic/motions/humanoid3d_walk.txt, context: {count: 2, starts: by_context}}")
                .find("one start clip per context: 2 contexts, 1 clips"),
            std::string::npos);
  EXPECT_NE(error("{name: imitation, clip: deepmimic/motions/humanoid3d_walk.txt, context: {count: 2, starts: sometimes}}")
                .find("starts"),
            std::string::npos);
}

TEST(ImitationEnv, TheConfigTakesOneClipOrAList) {
  MIMIC_NEED_HUMANOID();
  const YamlReader r("test.yaml");
  auto observation_size = [&](const std::string& env_yaml) {
    const EnvFactory f = make_env_factory(r.parse(env_yaml, ""), r);
    return f()->observation_size();
  };
  EXPECT_EQ(observation_size("{name: imitation, clip: [deepmimic/motions/humanoid3d_walk.txt, deepmimic/motions/humanoid3d_run.txt]}"),
            observation_size("{name: imitation, clip: deepmimic/motions/humanoid3d_walk.txt}"));
  auto error = [&](const std::string& env_yaml) { return factory_error(r, env_yaml); };
  EXPECT_NE(error("{name: imitation, clip: []}").find("'env.clip': an empty list"), std::string::npos);
  // Every clip of the list is loaded: a missing second one is named.
  EXPECT_NE(error("{name: imitation, clip: [deepmimic/motions/humanoid3d_walk.txt, /nonexistent/run.txt]}").find("/nonexistent/run.txt not found"),
            std::string::npos);
}

namespace {

// The root's position in frame `f` (oldest first) of a "links" observation.
Vec3 links_root(const Eigen::VectorXd& obs, int f, int joints) { return obs.segment(f * 7 * joints, 3); }

}  // namespace

TEST(ImitationEnv, MocapStartsFillTheLinkHistoryWithTheClipsEarlierPoses) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = moved(*test::humanoid3d_motion(ch, "humanoid3d_walk.txt"), -2.5, Vec3(-4, 7, 0));
  ImitationEnvConfig cfg;
  cfg.init_noise = 0.0;
  cfg.env.observations = ObservationConfig{.names = {"links"}, .link_history = 5};
  auto env = make_imitation_env(ch, walk, cfg);
  const int nj = ch.skeleton.num_joints();
  ASSERT_EQ(env->observation_size(), 5 * 7 * nj);
  // A start at a known time: the oldest frame is the clip's root 4 control steps earlier, seen
  // from the heading frame of the start.
  const double t = 0.5, dt = 1.0 / 30;
  const Eigen::VectorXd at = env->reset(env->state_on_clip(*walk, t));
  const Vec3 expected = HeadingFrame::of(walk->sample(t)).to_local(walk->sample(t - 4 * dt).root_pos);
  EXPECT_LT((links_root(at, 0, nj) - expected).norm(), 1e-6);
  EXPECT_GT(expected.norm(), 0.05);  // the walk moved: not the start repeated
  // Random starts moved to the track keep the motion that led to them: the root came from
  // behind (-X in the heading frame) at walking speed, over 4 steps.
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    std::mt19937_64 rng(seed);
    const Eigen::VectorXd obs = env->reset(rng);
    const Vec3 travelled = links_root(obs, 4, nj) - links_root(obs, 0, nj);
    EXPECT_GT(travelled.x(), 0.5 * 4 * dt) << "seed " << seed;
    EXPECT_LT(travelled.norm(), 3.0 * 4 * dt) << "seed " << seed;
  }
}

TEST(ImitationEnv, FixedPoseStartsAreTheRestPoseUpToNoise) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init = Init::FixedPose;
  cfg.init_noise = 0.02;
  auto env = make_imitation_env(ch, test::humanoid3d_motion(ch, "humanoid3d_walk.txt"), cfg);
  const Pose rest = rest_pose(ch.skeleton, Vec3(0, 0, ch.rest_root_height() + 1e-3));
  std::vector<Pose> starts;
  for (const std::uint64_t seed : {1u, 2u}) {
    std::mt19937_64 rng(seed);
    env->reset(rng);
    const Pose p = env->world().pose();
    EXPECT_TRUE(p.root_pos.isApprox(rest.root_pos, 1e-12));
    EXPECT_LT(rotation_distance(p.rot[0], Quat::Identity()), 1e-12);
    EXPECT_LE(max_joint_difference(p, rest),
              std::sqrt(3.0) * 0.02 + 1e-9);  // per-axis noise of 0.02
    const mjModel* m = env->world().model();
    for (int i = 0; i < m->nv; ++i) EXPECT_EQ(env->world().data()->qvel[i], 0.0);
    starts.push_back(p);
  }
  EXPECT_GT(max_joint_difference(starts[0], starts[1]), 1e-4);  // the noise differs per draw
  cfg.init_noise = 0.0;
  auto exact = make_imitation_env(ch, nullptr, cfg);
  std::mt19937_64 rng(5);
  exact->reset(rng);
  EXPECT_LT(max_joint_difference(exact->world().pose(), rest), 1e-12);
}

namespace {

// Steps with zero actions until the episode ends; returns the number of steps.
int run_zero_actions(CharacterEnv& env, StepResult& last) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
  int steps = 0;
  do {
    last = env.step(zero);
    ++steps;
  } while (!last.done());
  return steps;
}

}  // namespace

TEST(ImitationEnv, EpisodesEndAtTheTimeLimit) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto kick = test::humanoid3d_motion(ch, "humanoid3d_kick.txt");  // non-cyclic, 1.53 s
  ImitationEnvConfig cfg;
  cfg.init = Init::FixedPose;
  cfg.env.max_seconds = 2.0;
  // Standing at rest with zero actions lasts, past the end of the clip, to the limit.
  auto env = make_imitation_env(ch, kick, cfg);
  std::mt19937_64 rng(1);
  env->reset(rng);
  StepResult r;
  EXPECT_EQ(run_zero_actions(*env, r), 60);
  EXPECT_EQ(r.termination, Termination::TimeLimit);
  EXPECT_FALSE(is_failure(r.termination));
  EXPECT_GT(env->world().pose().root_pos.z(), 0.8);
  // Mocap starts count the limit from the episode's start, not from the clip time drawn (zero
  // actions topple a walking pose only after about 1 s).
  cfg.init = Init::Mocap;
  cfg.env.max_seconds = 0.5;
  auto mocap = make_imitation_env(ch, test::humanoid3d_motion(ch, "humanoid3d_walk.txt"), cfg);
  for (const std::uint64_t seed : {1u, 2u}) {
    std::mt19937_64 draw(seed);
    mocap->reset(draw);
    EXPECT_EQ(run_zero_actions(*mocap, r), 15) << "seed " << seed;
    EXPECT_EQ(r.termination, Termination::TimeLimit);
  }
}

// Seed 004 §5.2: an episode started on a non-cyclic clip ends where the clip ends; a cyclic one
// runs to the time limit.
TEST(ImitationEnv, MocapStartsOnANonCyclicClipEndWithTheClip) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const int elbow = ch.skeleton.find("right_elbow");
  ASSERT_GE(elbow, 0);
  const Joint& joint = ch.skeleton.joints[static_cast<std::size_t>(elbow)];
  // 1 s standing, the right elbow at 0.2 + 0.5 t rad: the start's clip time reads off the elbow.
  Clip clip;
  clip.name = "elbow_ramp";
  clip.skeleton = ch.skeleton;
  for (int f = 0; f <= static_cast<int>(clip.fps); ++f) {
    Pose p = rest_pose(ch.skeleton, Vec3(0, 0, ch.rest_root_height() + 0.01));
    p.rot[static_cast<std::size_t>(elbow)] = Quat(Eigen::AngleAxisd(0.2 + 0.5 * f / clip.fps, joint.axis));
    clip.frames.push_back(p);
  }
  ASSERT_EQ(clip.loop, LoopMode::None);
  ImitationEnvConfig cfg;
  cfg.init_noise = 0.0;
  cfg.env.max_seconds = 2.0;
  auto env = make_imitation_env(ch, std::make_shared<const Clip>(clip), cfg);
  const double dt = 1.0 / 30;
  std::mt19937_64 rng(3);
  StepResult r;
  for (int i = 0; i < 4; ++i) {
    env->reset(rng);
    const double t0 = (revolute_angle(joint, env->world().pose().rot[static_cast<std::size_t>(elbow)]) - 0.2) / 0.5;
    ASSERT_GE(t0, 0.0);
    ASSERT_LE(t0, 1.0);
    const int expected = std::max(1, static_cast<int>(std::ceil((1.0 - t0) / dt - 1e-6)));
    EXPECT_EQ(run_zero_actions(*env, r), expected) << "start at " << t0 << " s";
    EXPECT_EQ(r.termination, Termination::ClipEnd);
    EXPECT_FALSE(is_failure(r.termination));
  }
  // The same clip looping: to the limit. A start set directly (evaluation's) has no clip end.
  clip.loop = LoopMode::Wrap;
  auto cyclic = make_imitation_env(ch, std::make_shared<const Clip>(clip), cfg);
  cyclic->reset(rng);
  EXPECT_EQ(run_zero_actions(*cyclic, r), 60);
  EXPECT_EQ(r.termination, Termination::TimeLimit);
  env->reset(env->state_on_clip(clip, 0.9));
  EXPECT_EQ(run_zero_actions(*env, r), 60);
  EXPECT_EQ(r.termination, Termination::TimeLimit);
}

// Start clips (switching: another skill's motion): a share of the episodes starts from them, the
// rest from the skill's own clips; such an episode on a one-shot skill lasts one whole own clip.
TEST(ImitationEnv, StartClipsStartTheirShareOfEpisodesFromOtherMotion) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init_noise = 0.0;
  cfg.start_clip_share = 0.25;
  const auto own = held_elbow(ch, 0.3, 1.0);  // non-cyclic, 1 s
  const std::vector<std::shared_ptr<const Clip>> other{held_elbow(ch, 1.2, 2.0)};
  auto env = make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{own}, cfg, other);
  EXPECT_NEAR(starts_at_1_2_of_400(*env, 11) / 400.0, 0.25, 0.065);  // binomial sd 0.022
  std::mt19937_64 rng(11);
  // All from the other motion: each episode runs the own clip's whole second (30 control steps),
  // wherever in the other clip it started, and ends as the clip does, not as a failure.
  cfg.start_clip_share = 1.0;
  auto all = make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{own}, cfg, other);
  StepResult r;
  for (int i = 0; i < 3; ++i) {
    all->reset(rng);
    EXPECT_NEAR(elbow_angle(*all), 1.2, 1e-6);
    EXPECT_EQ(run_zero_actions(*all, r), 30);
    EXPECT_EQ(r.termination, Termination::ClipEnd);
  }
  // A share without start clips, a start clip that does not fit, a share outside [0, 1].
  EXPECT_THROW(make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{own}, cfg), Error);
  Clip unfit = *held_elbow(ch, 1.2, 2.0);
  unfit.skeleton.joints.pop_back();
  for (Pose& p : unfit.frames) p.rot.pop_back();
  EXPECT_THROW(make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{own}, cfg, {std::make_shared<const Clip>(unfit)}), Error);
  cfg.start_clip_share = 1.5;
  EXPECT_THROW(make_imitation_env(ch, std::vector<std::shared_ptr<const Clip>>{own}, cfg, other), Error);
}

TEST(ImitationEnv, TheStartClipKeysReachTheEnv) {
  MIMIC_NEED_HUMANOID();
  const YamlReader r("test.yaml");
  const std::string walk = "clip: deepmimic/motions/humanoid3d_walk.txt";
  auto error = [&](const std::string& env_yaml) { return factory_error(r, env_yaml); };
  EXPECT_EQ(error("{name: imitation, " + walk + ", start_clips: [deepmimic/motions/humanoid3d_run.txt]}"), "no error");
  EXPECT_NE(error("{name: imitation, " + walk + ", start_clip_share: 0.5}").find("'env.start_clip_share': no 'env.start_clips'"),
            std::string::npos);
  EXPECT_NE(error("{name: imitation, " + walk + ", start_clips: [/nonexistent/run.txt]}").find("/nonexistent/run.txt not found"),
            std::string::npos);
  EXPECT_NE(error("{name: imitation, " + walk + ", init: fixed, start_clips: [deepmimic/motions/humanoid3d_run.txt]}")
                .find("'env.start_clips' replace mocap starts: they need 'init: mocap'"),
            std::string::npos);
  // The share's default with start clips is three quarters: about 300 of 400 starts run (the run is
  // told from the walk by its root speed at the start: the run clip's is above 3 m/s).
  const EnvFactory f = make_env_factory(r.parse("{name: imitation, " + walk + ", init_noise: 0, start_clips: [deepmimic/motions/humanoid3d_run.txt]}", ""), r);
  const std::unique_ptr<Env> env = f();
  auto& c = dynamic_cast<CharacterEnv&>(*env);
  std::mt19937_64 rng(2);
  int running = 0;
  for (int i = 0; i < 400; ++i) {
    c.reset(rng);
    if (c.world().velocity().root_lin.norm() > 2.5) ++running;
  }
  EXPECT_NEAR(running / 400.0, 0.75, 0.065);
}

TEST(ImitationEnv, FallingEndsTheEpisodeEarly) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init = Init::FixedPose;
  cfg.env.max_seconds = 3.0;
  auto env = make_imitation_env(ch, nullptr, cfg);
  // Standing but pitched 0.8 rad forward and held rigid by zero actions: it topples onto its face.
  InitState s{rest_pose(ch.skeleton, Vec3(0, 0, ch.rest_root_height() + 0.05)), PoseVelocity{},
              0.0, {}};
  s.pose.rot[0] = axis_rotation('y', 0.8);
  s.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
  env->reset(s);
  StepResult r;
  run_zero_actions(*env, r);
  EXPECT_EQ(r.termination, Termination::Fall);
  EXPECT_TRUE(is_failure(r.termination));
  EXPECT_LT(env->elapsed(), 2.0);
}

TEST(ImitationEnv, FallLinksChooseWhichContactsEndTheEpisode) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init = Init::FixedPose;
  cfg.env.max_seconds = 1.0;
  StepResult r;
  std::mt19937_64 rng(1);
  // Standing at rest: DeepMimic's root, chest and neck never touch, the feet always do.
  auto standing = make_imitation_env(ch, nullptr, cfg);
  standing->reset(rng);
  EXPECT_EQ(run_zero_actions(*standing, r), 30);
  EXPECT_EQ(r.termination, Termination::TimeLimit);
  // The config's key reaches the env: a foot as a fall body ends the first step.
  const YamlReader yaml("test.yaml");
  const EnvFactory factory = make_env_factory(yaml.parse("{name: imitation, init: fixed, fall_links: [right_ankle]}", ""), yaml);
  const std::unique_ptr<Env> on_feet = factory();
  on_feet->reset(rng);
  r = on_feet->step(Eigen::VectorXd::Zero(on_feet->action_size()));
  EXPECT_EQ(r.termination, Termination::Fall);
  cfg.env.fall_links = {"right_foot"};
  EXPECT_THROW(
      {
        try {
          make_imitation_env(ch, nullptr, cfg);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("'fall_links' names 'right_foot', a body"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
}

// Holding the start pose while the walk (turned and moved off the track) goes on at about 1 m/s:
// with max_drift 0.1 the episode ends as Drift, a failure, on the first step the root is more than
// 0.1 m from the start's clip played on from the start and placed as the start was; without it
// the same steps go on. The expected root is computed here from the clip directly: the clip's
// displacement since the start, turned into the start's heading frame.
TEST(ImitationEnv, MaxDriftEndsAMocapStartThatFallsBehindItsClip) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = moved(*test::humanoid3d_motion(ch, "humanoid3d_walk.txt"), -2.5, Vec3(-4, 7, 0));
  auto run = [&](double max_drift) {
    ImitationEnvConfig cfg;
    cfg.init_noise = 0.0;
    cfg.env.max_drift = max_drift;
    auto env = make_imitation_env(ch, walk, cfg);
    std::mt19937_64 rng(5);
    env->reset(rng);
    const StartSource& source = env->start_source();
    EXPECT_EQ(source.clip, walk);
    const double t0 = source.time;
    const Quat undo = heading_rotation(-heading_angle(walk->sample(t0).rot[0]));
    const Vec3 start = env->world().root_position();
    EXPECT_LT(env->drift(), 1e-9);  // starts on its clip's root
    const Eigen::VectorXd hold = env->action_for(env->world().pose());
    std::vector<double> drifts;
    StepResult r;
    do {
      r = env->step(hold);
      const Vec3 there = start + undo * (walk->sample(t0 + env->elapsed()).root_pos - walk->sample(t0).root_pos);
      const Vec3 offset = env->world().root_position() - there;
      EXPECT_NEAR(env->drift(), std::hypot(offset.x(), offset.y()), 1e-9);
      // The pose drawn as the ghost: the clip's, moved as the start was; its root is `there`, and
      // its heading the clip's turn since the start (the start faces +x).
      const std::optional<Pose> ghost = env->reference_pose();
      EXPECT_TRUE(ghost.has_value());
      if (ghost) {
        EXPECT_LT((ghost->root_pos - there).norm(), 1e-9);
        const double turned = heading_angle(walk->sample(t0 + env->elapsed()).rot[0]) - heading_angle(walk->sample(t0).rot[0]);
        EXPECT_NEAR(std::remainder(heading_angle(ghost->rot[0]) - turned, 2 * kPi), 0.0, 1e-9);
      }
      drifts.push_back(env->drift());
    } while (!r.done() && drifts.size() < 300);
    return std::pair(r.termination, drifts);
  };
  const auto [ended, drifts] = run(0.1);
  EXPECT_EQ(ended, Termination::Drift);
  EXPECT_TRUE(is_failure(ended));
  EXPECT_GT(drifts.back(), 0.1);
  for (std::size_t i = 0; i + 1 < drifts.size(); ++i) EXPECT_LE(drifts[i], 0.1) << i;
  const auto [ended_without, drifts_without] = run(0.0);
  EXPECT_NE(ended_without, Termination::Drift);
  ASSERT_GT(drifts_without.size(), drifts.size());
  for (std::size_t i = 0; i < drifts.size(); ++i) EXPECT_DOUBLE_EQ(drifts_without[i], drifts[i]) << i;
  // A start set directly (evaluation's) has no source: nothing to drift from.
  ImitationEnvConfig cfg;
  cfg.env.max_drift = 0.3;
  auto env = make_imitation_env(ch, walk, cfg);
  env->reset(env->state_on_clip(*walk, 0.2));
  EXPECT_EQ(env->start_source().clip, nullptr);
  env->step(env->action_for(walk->sample(0.0)));
  EXPECT_EQ(env->drift(), 0.0);
  EXPECT_FALSE(env->reference_pose().has_value());
}

TEST(ImitationEnv, MaxDriftNeedsMocapStarts) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  ImitationEnvConfig cfg;
  cfg.init = Init::FixedPose;
  cfg.env.max_drift = 0.5;
  try {
    make_imitation_env(ch, nullptr, cfg);
    FAIL() << "max_drift without a clip to measure against";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("max_drift"), std::string::npos) << e.what();
  }
  const YamlReader r("test.yaml");
  const std::string message = factory_error(r, "{name: imitation, init: fixed,\n max_drift: 0.5}");
  EXPECT_NE(message.find("test.yaml:2"), std::string::npos) << message;
  EXPECT_NE(message.find("'env.max_drift'"), std::string::npos) << message;
  EXPECT_NE(factory_error(r, "{name: imitation, max_drift: -1}").find("max_drift"), std::string::npos);
  // fall_height measures against a reference, which the imitation environment has not: an error,
  // not a key that silently does nothing.
  const std::string no_reference = factory_error(r, "{name: imitation,\n fall_height: 0.5}");
  EXPECT_NE(no_reference.find("test.yaml:2"), std::string::npos) << no_reference;
  EXPECT_NE(no_reference.find("'env.fall_height'"), std::string::npos) << no_reference;
}

namespace {

// The character env's configuration as the factory makes it from an `env` section.
CharacterEnvConfig made_config(const YamlReader& yaml, const std::string& env_yaml) {
  const std::unique_ptr<Env> env = make_env_factory(yaml.parse(env_yaml, ""), yaml)();
  return dynamic_cast<const CharacterEnv&>(*env).config();
}

}  // namespace

// env.pd_limit reaches the simulation, in both humanoid environments; Spring by default (the
// committed models were trained under it); anything else is an error naming the key.
TEST(ImitationEnv, PdLimitKeyReachesTheWorld) {
  MIMIC_NEED_HUMANOID();
  const YamlReader yaml("test.yaml");
  auto limit_of = [&](const std::string& env_yaml) {
    const std::unique_ptr<Env> env = make_env_factory(yaml.parse(env_yaml, ""), yaml)();
    return dynamic_cast<const CharacterEnv&>(*env).world().config().pd_limit;
  };
  EXPECT_EQ(limit_of("{name: imitation, init: fixed}"), PdLimit::Spring);
  EXPECT_EQ(limit_of("{name: imitation, init: fixed, pd_limit: total}"), PdLimit::Total);
  EXPECT_EQ(limit_of("{name: tracking}"), PdLimit::Spring);
  EXPECT_EQ(limit_of("{name: tracking, pd_limit: total}"), PdLimit::Total);
  const std::string bad = factory_error(yaml, "{name: imitation, pd_limit: both}");
  EXPECT_NE(bad.find("pd_limit"), std::string::npos) << bad;
  EXPECT_NE(bad.find("total"), std::string::npos) << bad;
}

TEST(ImitationEnv, LiftStartsKeyReachesTheEnv) {
  MIMIC_NEED_HUMANOID();
  const YamlReader yaml("test.yaml");
  auto lifts = [&](const std::string& env_yaml) { return made_config(yaml, env_yaml).lift_starts; };
  EXPECT_FALSE(lifts("{name: imitation}"));
  EXPECT_TRUE(lifts("{name: imitation, lift_starts: true}"));
  EXPECT_FALSE(lifts("{name: tracking}"));
  EXPECT_TRUE(lifts("{name: tracking, lift_starts: true}"));
  const std::string bad = factory_error(yaml, "{name: tracking, lift_starts: maybe}");
  EXPECT_NE(bad.find("lift_starts"), std::string::npos) << bad;
}

TEST(ImitationEnv, StartMomentumKeysReachTheEnv) {
  MIMIC_NEED_HUMANOID();
  const YamlReader yaml("test.yaml");
  auto smoothing = [&](const std::string& env_yaml) { return made_config(yaml, env_yaml).start_momentum; };
  using Statistic = StartMomentumSmoothing::Statistic;
  const StartMomentumSmoothing plain = smoothing("{name: imitation}");
  EXPECT_EQ(plain.window, 0.0);
  EXPECT_EQ(plain.statistic, Statistic::Mean);
  EXPECT_TRUE(plain.linear);
  EXPECT_EQ(smoothing("{name: imitation, start_momentum_window: 0.1}").window, 0.1);
  const StartMomentumSmoothing median = smoothing(
      "{name: imitation, start_momentum_window: 0.1, start_momentum_statistic: median, start_momentum_linear: false}");
  EXPECT_EQ(median.statistic, Statistic::Median);
  EXPECT_FALSE(median.linear);
  const std::string bad = factory_error(yaml, "{name: imitation, start_momentum_window: -1}");
  EXPECT_NE(bad.find("start_momentum_window"), std::string::npos) << bad;
  const std::string bad_statistic =
      factory_error(yaml, "{name: imitation, start_momentum_window: 0.1, start_momentum_statistic: mode}");
  EXPECT_NE(bad_statistic.find("start_momentum_statistic"), std::string::npos) << bad_statistic;
  // Without a window the keys would do nothing: an error, not a silent no-op. A window of 0 given
  // with them turns the smoothing off on purpose (eval --set env.start_momentum_window=0).
  const std::string no_window = factory_error(yaml, "{name: imitation, start_momentum_linear: false}");
  EXPECT_NE(no_window.find("needs a start_momentum_window"), std::string::npos) << no_window;
  EXPECT_EQ(smoothing("{name: imitation, start_momentum_window: 0, start_momentum_statistic: median}").window, 0.0);
}

// env.terrain, env.pushes and the height map's keys reach the character environment, in both
// humanoid environments, and what they configure happens: the stairs are under the character's
// path, the height map sees them, and a sideways push moves the root sideways.
TEST(ImitationEnv, TerrainAndPushKeysReachTheEnv) {
  MIMIC_NEED_HUMANOID();
  const YamlReader yaml("test.yaml");
  const CharacterEnvConfig stairs = made_config(yaml, "{name: imitation, init: fixed, observations: [full_state, height_map], "
                                                      "height_map_size: 3, height_map_spacing: 0.5, height_map_ahead: 2.5, "
                                                      "terrain: {kind: stairs, start_zone: 1.0, step_height: 0.2, step_depth: 0.5}}");
  EXPECT_EQ(stairs.terrain.kind, TerrainKind::Stairs);
  EXPECT_EQ(stairs.terrain.step_height, 0.2);
  EXPECT_EQ(stairs.observations.height_map_size, 3);
  EXPECT_EQ(made_config(yaml, "{name: tracking}").terrain.kind, TerrainKind::Flat);
  EXPECT_EQ(stairs.terrain.levels, 0);
  EXPECT_EQ(made_config(yaml, "{name: imitation, terrain: {kind: stairs, levels: 6}}").terrain.levels, 6);  // a curriculum
  EXPECT_THROW(made_config(yaml, "{name: imitation, terrain: {kind: stairs, levels: -1}}"), Error);
  // The grid's centre is 2.4 m ahead of the root (at the origin, facing +x): x = 1.9, 2.4 and 2.9 m,
  // on the second, third and fourth steps (each 0.5 m deep from x = 1.0, 0.2 m higher than the
  // last), minus the root's height.
  const std::unique_ptr<Env> env = make_env_factory(yaml.parse("{name: imitation, init: fixed, init_noise: 0, observations: [height_map], "
                                                               "height_map_size: 3, height_map_spacing: 0.5, height_map_ahead: 2.4, "
                                                               "terrain: {kind: stairs, start_zone: 1.0, step_height: 0.2, step_depth: 0.5}}",
                                                               ""),
                                                    yaml)();
  std::mt19937_64 rng(1);
  const Eigen::VectorXd obs = env->reset(rng);
  ASSERT_EQ(obs.size(), 9);
  const double root_z = dynamic_cast<const CharacterEnv&>(*env).world().root_position().z();
  const auto& t = dynamic_cast<const CharacterEnv&>(*env).terrain();
  EXPECT_NEAR(t.height(2.25, 0.0), 0.6, 1e-9);  // the third step
  double highest = -1e9;
  for (int i = 0; i < obs.size(); ++i) highest = std::max(highest, obs[i] + root_z);
  EXPECT_NEAR(highest, 0.8, 1e-6);  // the fourth step's top, under the grid's far row

  // A 400 N push to the left (+y) on the chest for 0.2 s, 0.1 s into the episode.
  auto root_y_after = [&](const std::string& pushes) {
    const std::unique_ptr<Env> e =
        make_env_factory(yaml.parse("{name: tracking, clip: deepmimic/motions/humanoid3d_walk.txt, init: fixed" + pushes + "}", ""), yaml)();
    auto& c = dynamic_cast<CharacterEnv&>(*e);
    std::mt19937_64 r(1);
    c.reset(r);
    const double y0 = c.world().root_position().y();
    for (int i = 0; i < 12; ++i) c.step(c.action_for(c.world().pose()));
    return c.world().root_position().y() - y0;
  };
  const double pushed = root_y_after(", pushes: [{link: chest, force: [0, 400, 0], start: 0.1, duration: 0.2}]");
  const double left_alone = root_y_after("");
  EXPECT_GT(pushed - left_alone, 0.02) << pushed << " against " << left_alone;
  EXPECT_EQ(made_config(yaml, "{name: tracking, pushes: [{link: chest, force: [0, 400, 0], start: 0.1, duration: 0.2}]}").pushes.size(), 1u);

  // Errors name the key and its line.
  const std::string unknown_link = factory_error(yaml, "{name: imitation, init: fixed,\n pushes: [{link: tail, force: [1, 0, 0]}]}");
  EXPECT_NE(unknown_link.find("test.yaml:2"), std::string::npos) << unknown_link;
  EXPECT_NE(unknown_link.find("'env.pushes'"), std::string::npos) << unknown_link;
  EXPECT_NE(unknown_link.find("tail"), std::string::npos) << unknown_link;
  EXPECT_NE(factory_error(yaml, "{name: imitation, pushes: [{link: chest}]}").find("missing 'force'"), std::string::npos);
  EXPECT_NE(factory_error(yaml, "{name: imitation, pushes: [{link: chest, force: [1, 2]}]}").find("force"), std::string::npos);
  const CharacterEnvConfig walls = made_config(yaml, "{name: imitation, terrain: {kind: walls, wall_count: 2, wall_spacing: 4, wall_height: 1.5, "
                                                     "wall_thickness: 0.2, opening_width: 3}}");
  EXPECT_EQ(walls.terrain.kind, TerrainKind::Walls);
  EXPECT_EQ(walls.terrain.wall_count, 2);
  EXPECT_EQ(walls.terrain.wall_spacing, 4.0);
  EXPECT_EQ(walls.terrain.wall_height, 1.5);
  EXPECT_EQ(walls.terrain.wall_thickness, 0.2);
  EXPECT_EQ(walls.terrain.opening_width, 3.0);
  EXPECT_NE(factory_error(yaml, "{name: imitation, terrain: {kind: lava}}").find("env.terrain.kind"), std::string::npos);
  EXPECT_NE(factory_error(yaml, "{name: imitation, terrain: {kind: stairs, steps: 3}}").find("steps"), std::string::npos);
}

// `humanoid_forward`, the name models saved before the imitation environment had its own, makes
// the same environment.
TEST(ImitationEnv, HumanoidForwardIsTheImitationEnvironment) {
  MIMIC_NEED_HUMANOID();
  const YamlReader yaml("test.yaml");
  auto layout = [&](const std::string& name) {
    return make_env_factory(yaml.parse("{name: " + name + ", observations: [links, link_velocities], link_history: 5}", ""), yaml)()
        ->observation_size();
  };
  EXPECT_EQ(layout("humanoid_forward"), layout("imitation"));
  EXPECT_EQ(made_config(yaml, "{name: humanoid_forward, max_drift: 0.4}").max_drift, 0.4);
}

// allow_clip_contacts: a get-up's clip rests its back, hands and knees on the ground, so those stop
// being falls; the four Table 2 clips rest only their feet there (the run's shins reach 4 mm into the
// floor beside a planted foot, the knee high), so the recipe's rule changes nothing for
// them. Without the key every fall link stays.
TEST(ImitationEnv, BodiesTheClipPutsOnTheGroundAreNotFalls) {
  MIMIC_NEED_HUMANOID();
  const YamlReader yaml("test.yaml");
  const std::string recipe_falls =
      "fall_links: [root, chest, neck, right_hip, right_knee, right_shoulder, right_elbow, right_wrist, "
      "left_hip, left_knee, left_shoulder, left_elbow, left_wrist]";
  auto falls = [&](const std::string& clip, bool allow) {
    const std::unique_ptr<Env> env = make_env_factory(
        yaml.parse("{name: imitation, clip: deepmimic/motions/humanoid3d_" + clip + ".txt, " + recipe_falls +
                       (allow ? ", allow_clip_contacts: true}" : "}"),
                   ""),
        yaml)();
    return dynamic_cast<const CharacterEnv&>(*env).fall_bodies();
  };
  const std::vector<std::string> all = falls("walk", false);
  ASSERT_EQ(all.size(), 13u);
  for (const char* clip : {"walk", "run", "kick", "punch"}) EXPECT_EQ(falls(clip, true), all) << clip;
  // What each get-up's clip keeps as falls: the face-up one lies on its back and sits on its
  // shins, never on its thighs; the face-down one pushes up on hands, elbows and knees, its head
  // and shoulders off the ground.
  EXPECT_EQ(falls("getup_faceup", false), all);
  EXPECT_EQ(falls("getup_faceup", true), (std::vector<std::string>{"right_hip", "left_hip"}));
  EXPECT_EQ(falls("getup_facedown", true), (std::vector<std::string>{"neck", "right_shoulder", "left_shoulder"}));
  // The tracking env applies it to its reference.
  const std::unique_ptr<Env> tracking = make_env_factory(
      yaml.parse("{name: tracking, clip: deepmimic/motions/humanoid3d_getup_faceup.txt, " + recipe_falls + ", allow_clip_contacts: true}", ""),
      yaml)();
  EXPECT_EQ(dynamic_cast<const CharacterEnv&>(*tracking).fall_bodies(), falls("getup_faceup", true));
}
