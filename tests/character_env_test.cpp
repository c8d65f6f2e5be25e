// The simulated humanoid as an environment: sizes, actions, observations, terminations.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>

#include "core/error.hpp"
#include "env/character_env.hpp"
#include "motion/deepmimic.hpp"
#include "humanoid_data.hpp"

using namespace mimic;

namespace {

Eigen::Ref<const Eigen::VectorXd> part(const Eigen::VectorXd& obs, const CharacterEnv& env, const std::string& name) {
  for (const ObservationSlice& s : env.observation_layout())
    if (s.name == name) return obs.segment(s.offset, s.size);
  throw std::logic_error("no slice " + name);
}

}  // namespace

TEST(CharacterEnv, SizesOfActionsAndObservations) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  CharacterEnvConfig cfg;
  cfg.observations.names = {"full_state", "egocentric", "links", "link_velocities"};
  cfg.observations.link_history = 3;
  CharacterEnv env(ch, cfg);
  EXPECT_EQ(env.action_size(), 8 * 3 + 4);  // axis-angle per spherical joint, angle per knee/elbow
  // full_state: height 1 + root quat 4 + root velocities 6 + spherical (4 + 3) * 8 + revolute (1 + 1) * 4
  // egocentric: velocimeter, gyro, uprightness 9 + ankles, wrists and head 3 * 5
  const std::vector<int> sizes{75, 24, 3 * 7 * 15, 6 * 15};
  ASSERT_EQ(env.observation_layout().size(), sizes.size());
  int offset = 0;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(env.observation_layout()[i].size, sizes[i]) << env.observation_layout()[i].name;
    EXPECT_EQ(env.observation_layout()[i].offset, offset);
    offset += sizes[i];
  }
  EXPECT_EQ(env.observation_size(), offset);
  cfg.action_mode = ActionMode::Quaternion;
  EXPECT_EQ(CharacterEnv(ch, cfg).action_size(), 8 * 4 + 4);
}

TEST(CharacterEnv, ActionsBecomeClippedPdTargets) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  CharacterEnv env(ch, CharacterEnvConfig{});
  Eigen::VectorXd a = Eigen::VectorXd::Zero(env.action_size());
  a.segment(0, 3) << 0.3, -0.2, 0.1;  // chest, the first spherical joint
  a[3] = 100.0;                       // neck x: clipped to pi
  a[4] = std::nan("");                // neck y: not a number -> 0
  const Pose t = env.targets_from_action(a);
  EXPECT_LT(rotation_distance(t.rot[1], rotvec_to_quat(Vec3(0.3, -0.2, 0.1))), 1e-12);
  EXPECT_LT(rotation_distance(t.rot[2], rotvec_to_quat(Vec3(kPi, 0, 0))), 1e-12);
  // right_knee: the 7th action value after 2 spherical + right_hip; its limit is [-3.14, 0].
  Eigen::VectorXd knee = Eigen::VectorXd::Zero(env.action_size());
  knee[9] = 1.0;
  EXPECT_NEAR(revolute_angle(ch.skeleton.joints[4], env.targets_from_action(knee).rot[4]), 0.0, 1e-12);
  knee[9] = -1.0;
  EXPECT_NEAR(revolute_angle(ch.skeleton.joints[4], env.targets_from_action(knee).rot[4]), -1.0, 1e-12);
  EXPECT_THROW(env.targets_from_action(Eigen::VectorXd::Zero(5)), Error);
}

TEST(CharacterEnv, StandingWithZeroActionsRunsToTheTimeLimit) {
  MIMIC_NEED_HUMANOID();
  CharacterEnvConfig cfg;
  cfg.max_seconds = 2.0;
  CharacterEnv env(test::humanoid3d(), cfg);
  EXPECT_DOUBLE_EQ(env.control_dt(), 1.0 / 30.0) << "the world's control rate, known before any step";
  std::mt19937_64 rng(1);
  env.reset(rng);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(env.action_size());
  StepResult r;
  int steps = 0;
  do {
    const double before = env.physics_data()->time;
    r = env.step(zero);
    EXPECT_NEAR(env.physics_data()->time - before, env.control_dt(), 1e-9) << "step " << steps;
    ++steps;
  } while (!r.done());
  EXPECT_EQ(r.termination, Termination::TimeLimit);
  EXPECT_FALSE(is_failure(r.termination));
  EXPECT_EQ(steps, 60);
  EXPECT_GT(env.world().pose().root_pos.z(), 0.8);
}

TEST(CharacterEnv, TorsoOnTheGroundIsAFall) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  CharacterEnv env(ch, CharacterEnvConfig{});
  InitState lying{rest_pose(ch.skeleton, Vec3(0, 0, 0.1)), PoseVelocity{}, 0.0, {}};  // chest sphere touching
  lying.pose.rot[0] = axis_rotation('y', kPi / 2);  // face down
  lying.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
  env.reset(lying);
  const StepResult r = env.step(Eigen::VectorXd::Zero(env.action_size()));
  EXPECT_EQ(r.termination, Termination::Fall);
  EXPECT_TRUE(is_failure(r.termination));
  // The same with early termination off goes on.
  CharacterEnvConfig off;
  off.early_termination = false;
  CharacterEnv env2(ch, off);
  env2.reset(lying);
  EXPECT_EQ(env2.step(Eigen::VectorXd::Zero(env2.action_size())).termination, Termination::None);
}

TEST(CharacterEnv, NonCyclicReferenceEndsTheEpisode) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto kick = test::humanoid3d_motion(ch, "humanoid3d_kick.txt");
  CharacterEnvConfig cfg;
  cfg.early_termination = false;
  cfg.observations.names = {"phase"};
  CharacterEnv env(ch, cfg, kick);
  env.reset(init_state_from_clip(*kick, kick->duration() - 0.05));
  EXPECT_EQ(env.step(Eigen::VectorXd::Zero(env.action_size())).termination, Termination::None);
  EXPECT_EQ(env.step(Eigen::VectorXd::Zero(env.action_size())).termination, Termination::ClipEnd);
}

TEST(CharacterEnv, ObservationsAreInTheRightFrames) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  CharacterEnvConfig cfg;
  cfg.observations.names = {"egocentric", "links", "phase", "full_state"};
  CharacterEnv env(ch, cfg, walk);
  // Upright root turned to face +Y, moving along world +Y at 1 m/s, at 0.3 s on the clip.
  InitState s{rest_pose(ch.skeleton, Vec3(2, 3, 0.9)), PoseVelocity{}, 0.3, {}};
  s.pose.rot[0] = axis_rotation('z', kPi / 2);
  s.velocity.root_lin = Vec3(0, 1, 0);
  s.velocity.joint_ang.assign(ch.skeleton.joints.size(), Vec3::Zero());
  const Eigen::VectorXd obs = env.reset(s);
  const auto ego = part(obs, env, "egocentric");
  EXPECT_TRUE(ego.segment(0, 3).isApprox(Eigen::Vector3d(1, 0, 0), 1e-9));  // velocimeter: forward
  EXPECT_TRUE(ego.segment(6, 3).isApprox(Eigen::Vector3d(0, 0, 1), 1e-9));  // uprightness
  const auto links = part(obs, env, "links");
  EXPECT_TRUE(links.segment(0, 3).isApprox(Eigen::Vector3d(0, 0, 0.9), 1e-9));  // root over the heading origin
  EXPECT_TRUE(links.segment(3, 4).isApprox(Eigen::Vector4d(1, 0, 0, 0), 1e-9));  // no yaw left
  EXPECT_NEAR(part(obs, env, "phase")[0], 0.3 / walk->duration(), 1e-12);
  const auto full = part(obs, env, "full_state");
  EXPECT_NEAR(full[0], 0.9, 1e-12);
  EXPECT_TRUE(full.segment(1 + 4 + 8 * 4 + 4, 3).isApprox(Eigen::Vector3d(1, 0, 0), 1e-9));  // forward velocity
  CharacterEnvConfig bad;
  bad.observations.names = {"vision"};
  EXPECT_THROW(CharacterEnv(ch, bad), Error);
  bad.observations.names = {"phase"};
  EXPECT_THROW(CharacterEnv(ch, bad), Error);  // no reference clip
}

TEST(CharacterEnv, InitStateFromClipHasTheClipsVelocities) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  const auto vel = clip_velocities(*walk);
  const InitState s = init_state_from_clip(*walk, 10 / walk->fps);
  EXPECT_TRUE(s.velocity.root_lin.isApprox(vel[10].root_lin, 1e-9));
  EXPECT_TRUE(s.velocity.joint_ang[3].isApprox(vel[10].joint_ang[3], 1e-9));
  CharacterEnv env(ch, CharacterEnvConfig{}, walk);
  env.reset(s);
  // The simulation starts with the clip's root velocity.
  EXPECT_NEAR(env.world().data()->qvel[0], vel[10].root_lin.x(), 1e-9);
}

// The run clip's touchdown at 0.45 of its cycle puts a foot 4.9 cm into the floor. Started there,
// the contact throws the root upwards (1 m/s after one step where the clip falls at 1 m/s); with
// lift_starts the start, and its past poses, rise by that depth plus 1 mm and the foot lands.
TEST(CharacterEnv, LiftStartsRaisesAStartAndItsPastOutOfTheFloor) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto run = test::humanoid3d_motion(ch, "humanoid3d_run.txt");
  const InitState s = init_state_from_clip(*run, 0.45 * run->duration(), 2, 1.0 / 30);
  ASSERT_LT(s.velocity.root_lin.z(), -0.9);
  CharacterEnvConfig cfg;
  cfg.observations = {{"links"}, 3};
  CharacterEnv sunk(ch, cfg);
  const Eigen::VectorXd sunk_obs = sunk.reset(s);
  EXPECT_NEAR(sunk.world().root_position().z(), s.pose.root_pos.z(), 1e-9);
  const double depth = sunk.world().ground_penetration();
  EXPECT_GT(depth, 0.04);
  cfg.lift_starts = true;
  CharacterEnv lifted(ch, cfg);
  const Eigen::VectorXd lifted_obs = lifted.reset(s);
  EXPECT_NEAR(lifted.world().root_position().z(), s.pose.root_pos.z() + depth + 1e-3, 1e-9);
  EXPECT_EQ(lifted.world().ground_penetration(), 0.0);
  // Every frame of the history rises alike: link heights are world heights in the heading frame.
  const int per_frame = 7 * 15;
  for (int f = 0; f < 3; ++f)
    for (int j = 0; j < 15; ++j)
      EXPECT_NEAR(lifted_obs[f * per_frame + 7 * j + 2] - sunk_obs[f * per_frame + 7 * j + 2], depth + 1e-3, 1e-9) << "frame " << f;
  const Eigen::VectorXd hold = sunk.action_for(s.pose);
  sunk.step(hold);
  lifted.step(hold);
  EXPECT_GT(sunk.world().velocity().root_lin.z(), 0.8);
  EXPECT_LT(std::abs(lifted.world().velocity().root_lin.z()), 0.3);
}

// Frame differences give the run clip's touchdown (0.5 of its cycle) an angular momentum of
// 9 kg m^2/s and a sideways com velocity of 0.46 m/s for two frames; averaged over +-0.1 s they are
// under 2.5 and 0.2. A start smoothed so keeps its pose, joint velocities and com's vertical velocity,
// and, held on the clip's targets, strays sideways half as far in 0.3 s as a start with the
// instant's momentum. A clip whose momentum does not change (a pose sliding at 3 m/s) is left alone.
TEST(CharacterEnv, StartMomentumWindowSmoothsTheRunsTouchdownSpike) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto run = test::humanoid3d_motion(ch, "humanoid3d_run.txt");
  const double t = 0.5 * run->duration();
  CharacterEnvConfig cfg;
  cfg.observations = {{"links"}, 3};
  CharacterEnv raw_env(ch, cfg);
  cfg.start_momentum.window = 0.1;
  CharacterEnv smooth_env(ch, cfg);
  const InitState raw = raw_env.state_on_clip(*run, t), smooth = smooth_env.state_on_clip(*run, t);
  const BodyMomentum before = raw_env.world().momentum_of(raw.pose, raw.velocity);
  const BodyMomentum after = smooth_env.world().momentum_of(smooth.pose, smooth.velocity);
  EXPECT_GT(before.angular.norm(), 8.0);
  EXPECT_LT(after.angular.norm(), 2.5);
  EXPECT_GT(std::abs(before.com_velocity.y()), 0.4);
  EXPECT_LT(std::abs(after.com_velocity.y()), 0.2);
  EXPECT_NEAR(after.com_velocity.z(), before.com_velocity.z(), 1e-9);
  for (std::size_t j = 1; j < raw.velocity.joint_ang.size(); ++j) EXPECT_EQ(smooth.velocity.joint_ang[j], raw.velocity.joint_ang[j]);
  EXPECT_EQ(smooth.pose.root_pos, raw.pose.root_pos);
  ASSERT_EQ(smooth.past.size(), raw.past.size());
  auto sideways = [&](CharacterEnv& env, const InitState& s) {
    env.reset(s);
    for (int k = 1; k <= 9; ++k) env.step(env.action_for(run->sample(t + k / 30.0)));
    return std::abs(env.world().centre_of_mass().y() - before.com.y());
  };
  const double raw_stray = sideways(raw_env, raw), smooth_stray = sideways(smooth_env, smooth);
  EXPECT_GT(raw_stray, 0.1);
  EXPECT_LT(smooth_stray, 0.7 * raw_stray) << raw_stray;

  Clip slide;
  slide.skeleton = run->skeleton;
  for (int f = 0; f < 30; ++f) {
    Pose p = run->frames[0];
    p.root_pos.x() += 0.1 * f;
    slide.frames.push_back(p);
  }
  const InitState plain = raw_env.state_on_clip(slide, 0.5), kept = smooth_env.state_on_clip(slide, 0.5);
  EXPECT_LT((kept.velocity.root_lin - plain.velocity.root_lin).norm(), 1e-9);
  EXPECT_LT((kept.velocity.root_ang - plain.velocity.root_ang).norm(), 1e-9);
  EXPECT_NEAR(kept.velocity.root_lin.x(), 3.0, 1e-9);
  InitState s = raw;
  EXPECT_THROW(smooth_start_momentum(raw_env.world(), *run, t, StartMomentumSmoothing{}, s), Error);
}

// A median takes out a spike shorter than half the window where a mean only spreads it. The clip:
// a pose that steps 5 cm sideways between frames 14 and 15 (30 fps). Clip::sample's Catmull-Rom
// root and central differences over one frame give it, from 14.5 frames, 27/32 m/s sideways. The
// window +-0.1 s holds 17 states 0.375 frames apart; worked by hand in fractions, their sideways
// velocities are 0 five times, the spline's overshoot -9/512 and -225/4096 twice each, and eight
// positive ones: a mean of 8181/34816 m/s and a median of 0.
// Angular only (linear: false) spins the body about its centre of mass, which leaves the com's
// velocity as it was; at the run's touchdown the median brings |L| from 9 to under 1 kg m^2/s.
TEST(CharacterEnv, StartMomentumMedianRemovesAShortSpikeAndAngularOnlyKeepsTheComVelocity) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto run = test::humanoid3d_motion(ch, "humanoid3d_run.txt");
  CharacterEnvConfig cfg;
  CharacterEnv env(ch, cfg);
  Clip step;
  step.skeleton = run->skeleton;
  for (int f = 0; f < 30; ++f) {
    Pose p = run->frames[0];
    if (f >= 15) p.root_pos.y() += 0.05;
    step.frames.push_back(p);
  }
  const double t = 14.5 / 30;
  auto sideways = [&](StartMomentumSmoothing smoothing) {
    InitState s = init_state_from_clip(step, t);
    smooth_start_momentum(env.world(), step, t, smoothing, s);
    return env.world().momentum_of(s.pose, s.velocity).com_velocity.y();
  };
  EXPECT_NEAR(init_state_from_clip(step, t).velocity.root_lin.y(), 27.0 / 32, 1e-9);
  using Statistic = StartMomentumSmoothing::Statistic;
  EXPECT_NEAR(sideways({0.1, Statistic::Mean, true}), 8181.0 / 34816, 1e-9);
  EXPECT_NEAR(sideways({0.1, Statistic::Median, true}), 0.0, 1e-9);
  EXPECT_NEAR(sideways({0.1, Statistic::Median, false}), 27.0 / 32, 1e-9);

  const double touchdown = 0.5 * run->duration();
  const InitState raw = init_state_from_clip(*run, touchdown);
  InitState angular = raw;
  smooth_start_momentum(env.world(), *run, touchdown, {0.1, Statistic::Median, false}, angular);
  const BodyMomentum before = env.world().momentum_of(raw.pose, raw.velocity);
  const BodyMomentum after = env.world().momentum_of(angular.pose, angular.velocity);
  EXPECT_LT((after.com_velocity - before.com_velocity).norm(), 1e-9);
  EXPECT_GT(before.angular.norm(), 8.0);
  EXPECT_LT(after.angular.norm(), 1.0);
}

TEST(CharacterEnv, LinkHistoryKeepsTheLastKSteps) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  CharacterEnvConfig cfg;
  cfg.observations = {{"links"}, 2};
  CharacterEnv env(ch, cfg);
  std::mt19937_64 rng(3);
  const Eigen::VectorXd first = env.reset(rng);
  const int per_frame = 7 * 15;
  EXPECT_TRUE(first.head(per_frame).isApprox(first.tail(per_frame)));  // history padded with the first frame
  Eigen::VectorXd a = Eigen::VectorXd::Zero(env.action_size());
  a.segment(15, 3) << 0, -1.0, 0;  // right shoulder moves: the two frames now differ
  StepResult r = env.step(a);
  for (int i = 0; i < 3; ++i) r = env.step(a);
  EXPECT_GT((r.observation.head(per_frame) - r.observation.tail(per_frame)).norm(), 1e-3);
}

TEST(CharacterEnv, ActionForIsTheInverseOfTargetsFromAction) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  for (ActionMode mode : {ActionMode::AxisAngle, ActionMode::Quaternion}) {
    CharacterEnvConfig cfg;
    cfg.action_mode = mode;
    const CharacterEnv env(ch, cfg, walk);
    const Pose& p = walk->frames[11];
    const Eigen::VectorXd a = env.action_for(p);
    ASSERT_EQ(a.size(), env.action_size());
    const Pose back = env.targets_from_action(a);
    for (std::size_t j = 1; j < p.rot.size(); ++j)
      EXPECT_LT(rotation_distance(back.rot[j], p.rot[j]), 1e-9) << ch.skeleton.joints[j].name;
  }
  EXPECT_THROW((void)CharacterEnv(ch, {}, walk).action_for(Pose{}), Error);
}
