// The imitation environment's episode starts: at the track, from mocap (one clip or several, a
// chosen group, a context's clip), the link history, fixed poses, and start clips of other motion.
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
