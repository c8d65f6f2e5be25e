// How the imitation environment's episodes end (time limit, a one-shot clip's end, falls, the
// drift limit) and the character keys of a config reaching it.
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

// `fall_links: all` (the tracking recipe's, for any character): every body, less those the clip
// rests on. The walk keeps the 13 bodies the humanoid's explicit list names (all but the ankles);
// the dog's trot its lower legs. Without allow_clip_contacts the feet would fall at every step.
TEST(ImitationEnv, AllBodiesFallButThoseTheClipRestsOn) {
  MIMIC_NEED_HUMANOID();
  const YamlReader yaml("test.yaml");
  auto falls = [&](const std::string& rest) {
    const std::unique_ptr<Env> env = make_env_factory(yaml.parse("{name: tracking, " + rest + "}", ""), yaml)();
    return dynamic_cast<const CharacterEnv&>(*env).fall_bodies();
  };
  EXPECT_EQ(falls("clip: deepmimic/motions/humanoid3d_walk.txt, fall_links: all, allow_clip_contacts: true"),
            (std::vector<std::string>{"root", "chest", "neck", "right_hip", "right_knee", "right_shoulder", "right_elbow", "right_wrist",
                                      "left_hip", "left_knee", "left_shoulder", "left_elbow", "left_wrist"}));
  // The dog's trot spares the last two segments of each leg (hand and finger, foot and toe).
  EXPECT_EQ(falls("character: deepmimic/characters/dog3d.txt, clip: deepmimic/motions/dog3d_trot.txt, fall_links: all, allow_clip_contacts: true"),
            (std::vector<std::string>{"root", "spine0", "spine1", "neck", "head", "left_shoulder", "left_forearm", "right_shoulder",
                                      "right_forearm", "left_upper_leg", "left_leg", "right_upper_leg", "right_leg", "tail0", "tail1"}));
  EXPECT_THROW(
      {
        try {
          (void)falls("clip: deepmimic/motions/humanoid3d_walk.txt, fall_links: all");
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("set allow_clip_contacts: true"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
  EXPECT_THROW((void)falls("clip: deepmimic/motions/humanoid3d_walk.txt, fall_links: everything"), Error);
}
