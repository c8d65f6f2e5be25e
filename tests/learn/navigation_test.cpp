// Seed 000's high-level controller task (env/navigation_env.hpp, control/navigation.hpp): the
// view pinned on stairs of known heights and on a hand-rotated grid point, the action as the
// skill's heading target, progress as the reward, a fall as the end; and the environment by name
// over a runtime skill, with its errors.
#include "env/navigation_env.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "control/navigation.hpp"
#include "core/error.hpp"
#include "env/context_env.hpp"
#include "env/env_factory.hpp"
#include "env/imitation_env.hpp"
#include "steered_skill.hpp"
#include "../humanoid_data.hpp"

using namespace mimic;

namespace {

// The humanoid standing at the origin facing +x with a heading goal, on `terrain`.
std::unique_ptr<CharacterEnv> steered_env(const CharacterModel& ch, const TerrainSpec& terrain) {
  ImitationEnvConfig cfg;
  cfg.init = ImitationEnvConfig::Init::FixedPose;
  cfg.goal = ImitationEnvConfig::Goal::Heading;
  cfg.goal_period = 1e6;
  cfg.env.terrain = terrain;
  cfg.env.max_seconds = 60.0;
  return make_imitation_env(ch, nullptr, cfg);
}

}  // namespace

TEST(NavigationEnv, SeesTheStairsAheadAndCommandsTheSkillsHeading) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  TerrainSpec stairs;
  stairs.kind = TerrainKind::Stairs;  // from x = 2 m, steps 0.15 m high and 0.3 m deep
  NavigationConfig cfg;
  cfg.view_ahead = 3.0, cfg.view_width = 2.0, cfg.view_spacing = 0.1, cfg.decision_steps = 5, cfg.max_turn = 60.0;
  std::vector<double> seen_goals;
  auto inner = steered_env(ch, stairs);
  CharacterEnv* character = inner.get();
  NavigationEnv env(std::move(inner), [&](const Eigen::VectorXd& x) {
    seen_goals.push_back(std::atan2(x[x.size() - 1], x[x.size() - 2]));  // the goal closes the skill's frame
    return Eigen::VectorXd::Zero(character->action_size());
  }, 1, cfg);
  const auto layout = env.observation_layout();
  ASSERT_EQ(layout.size(), 3u);
  EXPECT_EQ(layout[0].size, 31 * 21);
  EXPECT_EQ(env.observation_size(), 31 * 21 + 3);
  EXPECT_EQ(env.action_size(), 1);
  EXPECT_DOUBLE_EQ(env.control_dt(), 5.0 / 30.0) << "a decision: 5 of the skill's 30 Hz steps";
  std::mt19937_64 rng(1);
  const Eigen::VectorXd obs = env.reset(rng);
  const Vec3 root = character->world().root_position();
  ASSERT_NEAR(root.x(), 0.0, 0.05);
  // Rows 2.1, 2.4 and 2.7 m ahead lie on steps 1, 2 and 3, across the whole view; row 1 m on the flat.
  for (int j = 0; j < 21; ++j) {
    EXPECT_NEAR(obs[10 * 21 + j], 0.0, 1e-9) << j;
    EXPECT_NEAR(obs[21 * 21 + j], 0.15, 1e-9) << j;
    EXPECT_NEAR(obs[24 * 21 + j], 0.30, 1e-9) << j;
    EXPECT_NEAR(obs[27 * 21 + j], 0.45, 1e-9) << j;
  }
  const int n = 31 * 21;
  EXPECT_NEAR(obs[n], 1.0, 1e-3);      // facing +x
  EXPECT_NEAR(obs[n + 1], 0.0, 1e-3);
  EXPECT_NEAR(obs[n + 2], root.y() / 10.0, 1e-12);  // over the course's half width (20 m wide)
  // A grid point by hand: 1 m ahead and 4 m to the right of (1, 2) facing +y is (5, 3).
  NavigationConfig wide;
  auto other = steered_env(ch, TerrainSpec{});
  const NavigationEnv view(std::move(other), [](const Eigen::VectorXd& x) { return Eigen::VectorXd::Zero(x.size()); }, 1, wide);
  const Eigen::Vector2d p = view.view_point(Vec3(1, 2, 0), kPi / 2, 2, 0);
  EXPECT_NEAR(p.x(), 5.0, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
  // An action of 0.5 commands 30 degrees from +x: the skill's target from the decision's first step.
  const double x0 = character->world().root_position().x();
  seen_goals.clear();
  const StepResult r = env.step(Eigen::VectorXd::Constant(1, 0.5));
  EXPECT_NEAR(goal_heading(*character), kPi / 6, 1e-12);
  ASSERT_EQ(seen_goals.size(), 5u);  // five control steps a decision
  EXPECT_NEAR(seen_goals.front(), kPi / 6, 0.05);  // (relative to a facing still near +x)
  ASSERT_EQ(r.reward_terms.size(), 1u);
  EXPECT_NEAR(r.reward(), character->world().root_position().x() - x0, 1e-12);  // metres along +x
  EXPECT_NEAR(env.command_of(2.0), kPi / 3, 1e-12);  // clipped to max_turn
  EXPECT_NEAR(env.command_of(std::nan("")), 0.0, 1e-12);
  EXPECT_THROW((void)env.step(Eigen::VectorXd::Zero(2)), Error);
  // Without the height map: only the heading and the lateral place, the same values.
  NavigationConfig blind_cfg = cfg;
  blind_cfg.height_map = false;
  auto blind_inner = steered_env(ch, stairs);
  NavigationEnv blind(std::move(blind_inner), [](const Eigen::VectorXd& x) { return Eigen::VectorXd::Zero(x.size()); }, 1, blind_cfg);
  const auto blind_layout = blind.observation_layout();
  ASSERT_EQ(blind_layout.size(), 2u);
  EXPECT_EQ(blind_layout[0].name, "heading");
  EXPECT_EQ(blind_layout[1].offset, 2);
  EXPECT_EQ(blind.observation_size(), 3);
  std::mt19937_64 same(1);
  const Eigen::VectorXd seen = blind.reset(same);
  ASSERT_EQ(seen.size(), 3);
  EXPECT_NEAR(seen[0], obs[n], 1e-12);
  EXPECT_NEAR(seen[2], obs[n + 2], 1e-12);
}

TEST(NavigationEnv, AFallOfTheSkillEndsTheEpisodeAsAFailure) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  auto inner = steered_env(ch, TerrainSpec{});
  const int actions = inner->action_size();
  NavigationConfig cfg;
  NavigationEnv env(std::move(inner), [actions](const Eigen::VectorXd&) { return Eigen::VectorXd::Constant(actions, 1.0); }, 1, cfg);
  std::mt19937_64 rng(3);
  env.reset(rng);
  StepResult r;
  int decisions = 0;
  while (!r.done() && decisions < 100) r = env.step(Eigen::VectorXd::Zero(1)), ++decisions;
  EXPECT_EQ(r.termination, Termination::Fall);  // limp, it folds long before the 30 s
  EXPECT_LT(decisions, 100);
  // A skill's environment without a heading goal cannot be steered.
  ImitationEnvConfig plain;
  plain.init = ImitationEnvConfig::Init::FixedPose;
  EXPECT_THROW(NavigationEnv(make_imitation_env(ch, nullptr, plain), [](const Eigen::VectorXd& x) { return x; }, 1, cfg), Error);
}

TEST(NavigationEnv, LeavingTheCourseSidewaysEndsTheEpisodeAsAFailure) {
  // The humanoid standing (zero actions hold it) 1.5 m and 2.5 m to the side of a course 4 m wide:
  // inside, the first decision goes on; outside, it ends the episode as a failure.
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  TerrainSpec course;
  course.kind = TerrainKind::Stairs;
  course.width = 4.0;
  for (const double y : {1.5, 2.5}) {
    auto inner = steered_env(ch, course);
    inner->set_init_sampler([&ch, y](std::mt19937_64&) {
      InitState s{rest_pose(ch.skeleton, Vec3(0, y, ch.rest_root_height() + 1e-3)), PoseVelocity{}, 0.0, {}};
      s.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
      return s;
    });
    const int actions = inner->action_size();
    NavigationEnv env(std::move(inner), [actions](const Eigen::VectorXd&) { return Eigen::VectorXd::Zero(actions); }, 1, NavigationConfig{});
    std::mt19937_64 rng(3);
    env.reset(rng);
    const StepResult r = env.step(Eigen::VectorXd::Zero(1));
    if (y < 2.0) EXPECT_FALSE(r.done()) << "inside the course";
    else EXPECT_EQ(r.termination, Termination::Fall) << "off the course";
  }
}

namespace {

std::string factory_error(const std::string& yaml) {
  const YamlReader r("navigation.yaml");
  try {
    (void)make_env_factory(r.parse(yaml, ""), r);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(NavigationEnv, IsBuiltByNameOverARuntimeSkillOnTheCourseGiven) {
  MIMIC_NEED_HUMANOID();
  register_control_envs();
  const auto steered = test::steered_skill_dir(true);
  const auto plain = test::steered_skill_dir(false);
  const YamlReader r("navigation.yaml");
  const EnvFactory f = make_env_factory(
      r.parse("{name: navigation, skill: " + steered.string() + ", terrain: {kind: walls}, decision_steps: 3, view_spacing: 1.0}", ""), r);
  const std::unique_ptr<Env> env = f();
  EXPECT_EQ(env->action_size(), 1);
  EXPECT_EQ(env->observation_size(), 16 * 9 + 3);
  CharacterEnv* character = character_of(*env);
  ASSERT_NE(character, nullptr);
  EXPECT_EQ(character->terrain().spec().kind, TerrainKind::Walls);
  std::mt19937_64 rng(2);
  env->reset(rng);
  const StepResult step = env->step(Eigen::VectorXd::Zero(1));
  EXPECT_TRUE(step.observation.allFinite());
  EXPECT_NE(env_names().find("navigation"), std::string::npos);
  EXPECT_NE(factory_error("{name: navigation}").find("'skill'"), std::string::npos);
  EXPECT_NE(factory_error("{name: navigation, skill: " + plain.string() + "}").find("must take a heading"), std::string::npos);
  EXPECT_NE(factory_error("{name: navigation, skill: " + steered.string() + ", decision_step: 3}").find("decision_step"), std::string::npos);
  EXPECT_NE(factory_error("{name: navigation, skill: /nonexistent/skill}").find("/nonexistent/skill"), std::string::npos);
}

TEST(Navigator, DrivesItsSkillOnItsCourseEveryDecision) {
  MIMIC_NEED_HUMANOID();
  register_control_envs();
  const auto steered = test::steered_skill_dir(true);
  // An untrained controller over the steered skill, on stairs, deciding every 4 steps.
  const std::string text = "seed: 3\niterations: 1\nenv: {name: navigation, skill: " + steered.string() +
                           ", terrain: {kind: stairs}, decision_steps: 4, view_ahead: 2, view_width: 1, view_spacing: 0.5, max_turn: 30}\n"
                           "collect: {envs: 1, threads: 1, samples: 16}\npolicy: {hidden: [8], activation: relu}\n"
                           "value: {hidden: [8], activation: relu}\n";
  Trainer trainer(parse_train_config(text, "hlc.yaml"));
  const auto dir = test::temp_dir("navigator");
  write_file_atomic(dir / "config.yaml", text);
  trainer.write_runtime_networks(dir / kRuntimeFileName);
  EXPECT_TRUE(is_navigation_model(dir));
  EXPECT_FALSE(is_navigation_model(steered));
  EXPECT_FALSE(is_navigation_model(dir / "nonexistent")) << "no config.yaml: not a navigation model";
  EXPECT_EQ(model_env_name(dir), "navigation");
  EXPECT_EQ(model_env_name(steered), "imitation");
  EXPECT_FALSE(env_has_character("navigation"));
  EXPECT_TRUE(env_has_character("imitation"));

  Navigator nav(dir);
  EXPECT_EQ(nav.config().decision_steps, 4);
  Controller c({nav.skill()}, 5);
  EXPECT_TRUE(c.steerable(nav.skill()->name()));
  // The skill walks on the controller's course: the first step up is 0.15 m high from x = 2 m.
  EXPECT_NEAR(c.ground_height(2.15, 0.0), 0.15, 1e-12);
  EXPECT_NEAR(c.ground_height(1.0, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(c.course_half_width(), 10.0, 1e-12);

  // At the episode's first step the controller decides, from the view of the state now.
  const NavigationView view(nav.config());
  ASSERT_EQ(view.size(), 5 * 3 + 3);
  const Eigen::VectorXd seen =
      view.observe(c.root_position(), c.facing(), [&c](double x, double y) { return c.ground_height(x, y); }, c.course_half_width());
  EXPECT_NEAR(seen[4 * 3 + 1], 0.15, 1e-12);  // 2 m straight ahead: the first step
  const double expected = view.command(nav.controller()->act(seen)[0]);
  EXPECT_TRUE(nav.drive(c));
  EXPECT_NEAR(c.heading(), expected, 1e-12);
  EXPECT_LE(std::abs(c.heading()), kPi / 6 + 1e-12);  // max_turn 30 degrees
  // Then not until decision_steps steps later.
  for (int k = 1; k < 4; ++k) {
    c.step();
    c.set_heading(1.0);  // a user's command, held until the next decision
    EXPECT_FALSE(nav.drive(c)) << k;
    EXPECT_DOUBLE_EQ(c.heading(), 1.0);
  }
  c.step();
  EXPECT_TRUE(nav.drive(c));
  EXPECT_LE(std::abs(c.heading()), kPi / 6 + 1e-12);
  // A model of another task is named.
  try {
    Navigator wrong(steered);
    ADD_FAILURE() << "a steered skill loaded as a navigation controller";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a navigation controller"), std::string::npos) << e.what();
  }
}
