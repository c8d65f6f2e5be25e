// Seed 003's tracking reward: each kernel against hand-computed values, the simulated state read
// back exactly as the reference's, and how tracking episodes start and end.
#include "env/tracking.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "core/yaml_reader.hpp"
#include "env/env_factory.hpp"
#include "humanoid_data.hpp"

using namespace mimic;

namespace {

// root (free) -> arm (spherical, 1 m along x) -> hand (fixed, 1 m further, an end effector).
Skeleton arm_skeleton() {
  Skeleton sk;
  auto add = [&](const char* name, int parent, JointType type, const Vec3& offset, bool end_effector) {
    Joint j;
    j.name = name, j.parent = parent, j.type = type, j.offset = offset, j.end_effector = end_effector;
    sk.joints.push_back(j);
  };
  add("root", -1, JointType::Free, Vec3::Zero(), false);
  add("arm", 0, JointType::Spherical, Vec3(1, 0, 0), false);
  add("hand", 1, JointType::Fixed, Vec3(1, 0, 0), true);
  return sk;
}

TrackedState state_of(const Skeleton& sk, const Pose& pose) {
  TrackedState s;
  s.pose = pose;
  s.velocity.joint_ang.assign(sk.joints.size(), Vec3::Zero());
  s.links = forward_kinematics(sk, pose);
  return s;
}

// A tracking env on `clip` from its first frame (FSI), reset.
std::unique_ptr<CharacterEnv> env_at_clip_start(const CharacterModel& ch, std::shared_ptr<const Clip> clip, TrackingConfig cfg) {
  cfg.init = TrackingConfig::Init::Fixed;
  auto env = make_tracking_env(ch, std::move(clip), cfg);
  std::mt19937_64 rng(1);
  env->reset(rng);
  return env;
}

double sum_of_terms(const StepResult& r) {
  double s = 0;
  for (const auto& [n, v] : r.reward_terms) s += v;
  return s;
}

}  // namespace

TEST(TrackingReward, IdenticalStatesScoreOneOnEveryTerm) {
  const Skeleton sk = arm_skeleton();
  Pose p = rest_pose(sk, Vec3(0.3, -0.2, 1.0));
  p.rot[0] = rotvec_to_quat(Vec3(0.1, 0.2, 1.3));
  p.rot[1] = rotvec_to_quat(Vec3(0.4, -0.3, 0.2));
  TrackedState s = state_of(sk, p);
  s.velocity.root_ang = Vec3(1, 2, 3);
  s.velocity.joint_ang[1] = Vec3(-1, 0.5, 2);
  s.com = Vec3(0.5, 0.1, 0.9);
  const TrackingTerms t = tracking_terms(sk, s, s);
  EXPECT_DOUBLE_EQ(t.pose, 1.0);
  EXPECT_DOUBLE_EQ(t.velocity, 1.0);
  EXPECT_DOUBLE_EQ(t.end_effector, 1.0);
  EXPECT_DOUBLE_EQ(t.com, 1.0);
}

TEST(TrackingReward, KnownOffsetsGiveHandComputedKernels) {
  const Skeleton sk = arm_skeleton();
  const Pose ref_pose = rest_pose(sk, Vec3(0, 0, 1));
  Pose sim_pose = ref_pose;
  sim_pose.rot[1] = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));  // the arm turned 0.3 rad
  const TrackedState ref = state_of(sk, ref_pose);
  TrackedState sim = state_of(sk, sim_pose);
  sim.velocity.root_ang = Vec3(0, 0, 1);  // the root spinning at 1 rad/s, the reference still
  sim.com = ref.com + Vec3(0.1, 0, 0);
  const TrackingTerms t = tracking_terms(sk, sim, ref);
  // Two tracked joints (root, arm; the hand is fixed): pose mean (0 + 0.3^2) / 2.
  EXPECT_NEAR(t.pose, std::exp(-2.0 * 0.09 / 2), 1e-12);
  // Velocity mean (1^2 + 0) / 2.
  EXPECT_NEAR(t.velocity, std::exp(-0.1 * 0.5), 1e-12);
  // The hand at (1 + cos 0.3, sin 0.3) from the root instead of (2, 0): |d|^2 = 2 - 2 cos 0.3.
  EXPECT_NEAR(t.end_effector, std::exp(-40.0 * (2 - 2 * std::cos(0.3))), 1e-12);
  EXPECT_NEAR(t.com, std::exp(-10.0 * 0.01), 1e-12);
  // Scales come from the config.
  const TrackingTerms half = tracking_terms(sk, sim, ref, TrackingScales{1.0, 0.05, 20.0, 5.0});
  EXPECT_NEAR(half.pose, std::exp(-0.09 / 2), 1e-12);
  EXPECT_NEAR(half.com, std::exp(-0.05), 1e-12);
  // The velocity kernel reads the centre of mass's velocity instead of its position.
  sim.com_velocity = ref.com_velocity + Vec3(0.5, 0, -0.1);
  EXPECT_NEAR(tracking_terms(sk, sim, ref, TrackingScales{}, ComTerm::Velocity).com, std::exp(-10.0 * 0.26), 1e-12);
  sim.com = ref.com;
  EXPECT_NEAR(tracking_terms(sk, sim, ref, TrackingScales{}, ComTerm::Velocity).com, std::exp(-10.0 * 0.26), 1e-12);
  EXPECT_DOUBLE_EQ(tracking_terms(sk, sim, ref).com, 1.0);  // position: unmoved
}

TEST(TrackingReward, TheRootTermWeighsPositionRotationAndVelocitiesAsDeepMimic) {
  const Skeleton sk = arm_skeleton();
  const Pose ref_pose = rest_pose(sk, Vec3(0, 0, 1));
  const TrackedState ref = state_of(sk, ref_pose);
  TrackedState sim = ref;
  EXPECT_DOUBLE_EQ(tracking_terms(sk, sim, ref).root, 1.0);
  sim.pose.root_pos += Vec3(0.1, 0, 0);                     // 0.1 m off: 0.01
  sim.pose.rot[0] = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitZ()));  // 0.2 rad: 0.1 * 0.04
  sim.velocity.root_lin = Vec3(1, 0, 0);                      // 1 m/s: 0.01 * 1
  sim.velocity.root_ang = Vec3(0, 0, 2);                      // 2 rad/s: 0.001 * 4
  // exp(-5 * (0.01 + 0.004 + 0.01 + 0.004)) = exp(-0.14)
  EXPECT_NEAR(tracking_terms(sk, sim, ref).root, std::exp(-0.14), 1e-12);
  TrackingScales scales;
  scales.root = 10;
  EXPECT_NEAR(tracking_terms(sk, sim, ref, scales).root, std::exp(-0.28), 1e-12);
  // The root's height counts as its horizontal place does.
  sim = ref;
  sim.pose.root_pos.z() -= 0.3;
  EXPECT_NEAR(tracking_terms(sk, sim, ref).root, std::exp(-5 * 0.09), 1e-12);
}

TEST(TrackingReward, EndEffectorsAreComparedInEachOwnHeadingFrame) {
  // The same pose turned about +Z and moved: hands relative to the root, each in its own
  // heading frame, are unchanged; the centre of mass and root rotation are not.
  const Skeleton sk = arm_skeleton();
  Pose a = rest_pose(sk, Vec3(0, 0, 1));
  a.rot[1] = rotvec_to_quat(Vec3(0.2, 0.3, 0.4));
  Pose b = a;
  b.root_pos = Vec3(3, -2, 1);
  b.rot[0] = heading_rotation(1.2) * a.rot[0];
  const TrackingTerms t = tracking_terms(sk, state_of(sk, b), state_of(sk, a));
  EXPECT_NEAR(t.end_effector, 1.0, 1e-12);
  EXPECT_NEAR(t.pose, std::exp(-2.0 * 1.2 * 1.2 / 2), 1e-12);
}

TEST(TrackingReward, SimulatedStateReadsBackAsTheReferenceAtTheStart) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  TrackingConfig cfg;
  cfg.init = TrackingConfig::Init::Fixed;
  auto env = make_tracking_env(ch, walk, cfg);
  const double t0 = 0.4;
  env->reset(init_state_from_clip(*walk, t0));
  const World& w = env->world();
  const MassModel masses(w);
  const TrackedState ref = reference_state(*walk, masses, t0);
  TrackedState sim{w.pose(), w.velocity(), w.link_frames(), w.centre_of_mass()};
  // World::velocity inverts set_state's velocities; the mass model places MuJoCo's centre of mass.
  for (std::size_t j = 0; j < ref.velocity.joint_ang.size(); ++j)
    EXPECT_LT((sim.velocity.joint_ang[j] - ref.velocity.joint_ang[j]).norm(), 1e-9) << ch.skeleton.joints[j].name;
  EXPECT_LT((sim.velocity.root_ang - ref.velocity.root_ang).norm(), 1e-9);
  EXPECT_LT((sim.velocity.root_lin - ref.velocity.root_lin).norm(), 1e-9);
  EXPECT_LT((sim.com - ref.com).norm(), 2e-3);
  EXPECT_GT(ch.total_mass(), 10.0);
  const TrackingTerms t = tracking_terms(ch.skeleton, sim, ref);
  EXPECT_GT(t.pose, 0.999);
  EXPECT_GT(t.velocity, 0.999);
  EXPECT_GT(t.end_effector, 0.99);
  EXPECT_GT(t.com, 0.999);
}

TEST(TrackingEnv, FollowingTheClipScoresHighAndAStillPoseScoresLow) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  TrackingConfig cfg;
  cfg.init = TrackingConfig::Init::Fixed;
  auto env = make_tracking_env(ch, walk, cfg);
  std::mt19937_64 rng(1);
  env->reset(rng);
  EXPECT_DOUBLE_EQ(env->time(), 0.0);
  // PD targets = the clip's next pose: the servos follow it for a few steps.
  double follow = 0, still = 0;
  auto targets = [&](const Pose& p) { return env->action_for(p); };
  for (int i = 1; i <= 5; ++i) follow += sum_of_terms(env->step(targets(walk->sample(i / 30.0))));
  env->reset(rng);
  const Eigen::VectorXd hold = targets(walk->sample(0.0));
  for (int i = 1; i <= 5; ++i) still += sum_of_terms(env->step(hold));
  EXPECT_GT(follow / 5, 0.6);
  EXPECT_LT(still, follow);
  const StepResult r = env->step(hold);
  ASSERT_EQ(r.reward_terms.size(), 4u);
  EXPECT_EQ(r.reward_terms[0].first, "pose");
  EXPECT_LE(r.reward_terms[0].second, 0.65);
  EXPECT_LE(r.reward_terms[2].second, 0.15);
}

// Started a metre to the side of the walk's reference two steps before a cycle ends: the root
// term sees the metre until the reference's next cycle begins, then (resync_root) the reference
// is moved onto the character and only the step's own error is left; without it, the metre stays.
TEST(TrackingEnv, ResyncMovesTheReferenceOntoTheCharacterAtANewCycle) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  ASSERT_EQ(walk->loop, LoopMode::Wrap);
  TrackingConfig cfg;
  cfg.init = TrackingConfig::Init::Fixed;
  cfg.weights = {0, 0, 0, 0, 1};  // the root term alone
  const double t0 = walk->duration() - 1.5 / 30;
  InitState start = init_state_from_clip(*walk, t0);
  start.pose.root_pos.y() += 1.0;
  const auto root_terms = [&](bool resync) {
    cfg.resync_root = resync;
    auto env = make_tracking_env(ch, walk, cfg);
    env->reset(start);
    std::vector<double> terms;
    for (int i = 0; i < 2; ++i) {
      const StepResult r = env->step(env->action_for(walk->sample(t0 + (i + 1) / 30.0)));
      EXPECT_EQ(r.reward_terms.back().first, "root");
      terms.push_back(r.reward_terms.back().second);
    }
    return terms;
  };
  const std::vector<double> off = root_terms(false), on = root_terms(true);
  EXPECT_LT(off[0], std::exp(-5 * 0.9));  // a metre: exp(-5) and the step's own error
  EXPECT_LT(off[1], std::exp(-5 * 0.9));
  EXPECT_DOUBLE_EQ(on[0], off[0]);        // the same cycle: nothing moved
  EXPECT_GT(on[1], 0.9);                  // the new cycle: the metre is gone
}

TEST(TrackingEnv, StartsFixedOrAnywhereOnTheClipAndEndsAsTheClipSays) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto kick = test::humanoid3d_motion(ch, "humanoid3d_kick.txt");
  ASSERT_EQ(kick->loop, LoopMode::None);
  TrackingConfig cfg;
  cfg.env.early_termination = false;
  auto rsi = make_tracking_env(ch, kick, cfg);
  std::mt19937_64 rng(3);
  std::vector<double> starts;
  for (int i = 0; i < 20; ++i) {
    rsi->reset(rng);
    starts.push_back(rsi->time());
    EXPECT_GE(rsi->time(), 0.0);
    EXPECT_LE(rsi->time(), kick->duration());
  }
  EXPECT_GT(*std::max_element(starts.begin(), starts.end()) - *std::min_element(starts.begin(), starts.end()), kick->duration() / 3);
  // A non-cyclic clip ends the episode at its end.
  cfg.init = TrackingConfig::Init::Fixed;
  auto fsi = make_tracking_env(ch, kick, cfg);
  fsi->reset(rng);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(fsi->action_size());
  int steps = 0;
  StepResult r;
  do r = fsi->step(zero), ++steps;
  while (!r.done() && steps < 1000);
  EXPECT_EQ(r.termination, Termination::ClipEnd);
  EXPECT_NEAR(steps, std::ceil(kick->duration() * 30 - 1e-6), 1);
}

// A crumpling character sinks below half the reference's root height before its torso touches
// the ground: the height rule ends the episode sooner, as a fall, with the torso still up.
TEST(TrackingEnv, SinkingBelowHalfTheReferencesRootHeightIsAFall) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  auto run = [&](double fall_height) {
    TrackingConfig cfg;
    cfg.env.max_seconds = 3.0;
    cfg.env.fall_height = fall_height;
    auto env = env_at_clip_start(ch, walk, cfg);
    const Eigen::VectorXd fold = env->action_for(test::folded(ch, walk->frames[0]));
    StepResult r;
    int steps = 0;
    do r = env->step(fold), ++steps;
    while (!r.done());
    EXPECT_EQ(r.termination, Termination::Fall);
    return std::tuple(steps, env->fall_contact(), env->world().pose().root_pos.z());
  };
  const auto [by_height, torso_down, height] = run(0.5);
  EXPECT_FALSE(torso_down);
  EXPECT_LT(height, 0.5 * walk->frames[0].root_pos.z() + 0.05);
  const auto [by_contact, torso_down_too, unused] = run(0.0);
  EXPECT_TRUE(torso_down_too);
  EXPECT_LT(by_height, by_contact);
}

// Holding the first pose while the walk goes on at about 1 m/s: with max_drift 0.3 the episode
// ends as Drift, a failure, on the first step the root is more than 0.3 m (horizontally) from the
// reference's; without it the same steps go on.
TEST(TrackingEnv, FallingBehindTheReferenceByMaxDriftEndsTheEpisodeAsAFailure) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  auto run = [&](double max_drift) {
    TrackingConfig cfg;
    cfg.env.max_drift = max_drift;
    auto env = env_at_clip_start(ch, walk, cfg);
    EXPECT_LT(env->drift(), 1e-9);  // starts on the reference's root
    const Eigen::VectorXd hold = env->action_for(walk->frames[0]);
    std::vector<double> drifts;
    StepResult r;
    do {
      r = env->step(hold);
      const Vec3 offset = env->world().root_position() - walk->sample(env->time()).root_pos;
      EXPECT_NEAR(env->drift(), std::hypot(offset.x(), offset.y()), 1e-12);
      drifts.push_back(env->drift());
    } while (!r.done() && drifts.size() < 300);
    return std::pair(r.termination, drifts);
  };
  const auto [ended, drifts] = run(0.3);
  EXPECT_EQ(ended, Termination::Drift);
  EXPECT_TRUE(is_failure(ended));
  EXPECT_STREQ(to_string(ended), "drift");
  EXPECT_GT(drifts.back(), 0.3);
  for (std::size_t i = 0; i + 1 < drifts.size(); ++i) EXPECT_LE(drifts[i], 0.3) << i;
  const auto [ended_without, drifts_without] = run(0.0);
  EXPECT_NE(ended_without, Termination::Drift);
  ASSERT_GT(drifts_without.size(), drifts.size());
  for (std::size_t i = 0; i < drifts.size(); ++i) EXPECT_DOUBLE_EQ(drifts_without[i], drifts[i]) << i;
}

// "reference_root": where the clip's root is, seen from the character's root in its heading frame.
TEST(TrackingEnv, ReferenceRootIsTheClipsRootInTheCharactersHeadingFrame) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  TrackingConfig cfg;
  cfg.env.observations.names = {"full_state", "reference_root", "phase"};
  auto env = env_at_clip_start(ch, walk, cfg);
  const ObservationSlice slice = env->observation_layout()[1];
  ASSERT_EQ(slice.name, "reference_root");
  ASSERT_EQ(slice.size, 3);
  InitState start = init_state_from_clip(*walk, 0.0);
  EXPECT_LT(env->reset(start).segment(slice.offset, 3).norm(), 1e-9);  // on the reference
  // Turned to face world +y and moved 1 m along +x and 0.1 m down: the reference's root lies 1 m
  // to the character's left (world -x) and 0.1 m above.
  const Vec3 root = start.pose.root_pos;
  const Quat turn = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ())) * HeadingFrame::of(start.pose).yaw.conjugate();
  start.pose.rot[0] = turn * start.pose.rot[0];
  start.pose.root_pos = root + Vec3(1.0, 0.0, -0.1);
  const Eigen::Vector3d seen = env->reset(start).segment(slice.offset, 3);
  EXPECT_NEAR(seen.x(), 0.0, 1e-9);
  EXPECT_NEAR(seen.y(), 1.0, 1e-9);
  EXPECT_NEAR(seen.z(), 0.1, 1e-9);
  // A cyclic clip's root moves on cycle by cycle: after a cycle and a half the reference is ahead.
  start.time = 1.5 * walk->duration();
  start.pose.root_pos = root;
  const Vec3 ahead = walk->sample(start.time).root_pos - root;
  EXPECT_NEAR(env->reset(start).segment(slice.offset, 3).head<2>().norm(), ahead.head<2>().norm(), 1e-9);
  EXPECT_GT(ahead.head<2>().norm(), 1.5);
  // It needs a clip.
  CharacterEnvConfig no_clip;
  no_clip.observations.names = {"full_state", "reference_root"};
  try {
    CharacterEnv bare(ch, no_clip, nullptr);
    FAIL() << "reference_root without a clip";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "observations: 'reference_root' needs a reference clip");
  }
}

// The reference's centre-of-mass velocity is its mean over the step; over a whole cycle of the
// walk those means add up to the cycle's displacement (about 1.24 m in 1.27 s).
TEST(TrackingReward, TheReferencesCentreOfMassVelocityIsItsMeanOverTheStep) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  auto env = make_tracking_env(ch, walk, TrackingConfig{});
  const MassModel masses(env->world());
  const double dt = 1.0 / 30.0, t = 0.7;
  const TrackedState now = reference_state(*walk, masses, t, dt);
  const Vec3 expected = (now.com - reference_state(*walk, masses, t - dt).com) / dt;
  EXPECT_LT((now.com_velocity - expected).norm(), 1e-12);
  EXPECT_EQ(reference_state(*walk, masses, t).com_velocity, Vec3::Zero());  // without dt: not computed
  const int steps = 40;
  const double T = walk->duration(), step = T / steps;
  Vec3 mean = Vec3::Zero();
  for (int k = 1; k <= steps; ++k) mean += reference_state(*walk, masses, k * step, step).com_velocity / steps;
  const Vec3 cycle = reference_state(*walk, masses, T).com - reference_state(*walk, masses, 0).com;
  EXPECT_LT((mean - cycle / T).norm(), 1e-9);
  EXPECT_NEAR(mean.head<2>().norm(), 0.98, 0.02);  // the walk's pace (its root drift per cycle / T)
}

// com_term: velocity in the env: the reported term is the kernel of the simulated centre of mass's
// displacement over the step against the reference's.
TEST(TrackingEnv, AVelocityComTermComparesTheStepsMeanVelocities) {
  MIMIC_NEED_HUMANOID();
  const YamlReader reader("test.yaml");
  const EnvFactory f = make_env_factory(
      reader.parse("{name: tracking, clip: deepmimic/motions/humanoid3d_walk.txt, init: fixed, com_term: velocity, scales: {com: 1}}", "t"),
      reader);
  auto env_ptr = f();
  auto& env = dynamic_cast<CharacterEnv&>(*env_ptr);
  env.reset(init_state_from_clip(*env.reference(), 0.4));
  const MassModel masses(env.world());
  for (int k = 0; k < 3; ++k) {
    const Vec3 before = env.world().centre_of_mass();
    const StepResult r = env.step(Eigen::VectorXd::Zero(env.action_size()));
    const Vec3 v_sim = (env.world().centre_of_mass() - before) * 30.0;
    const Vec3 v_ref = reference_state(*env.reference(), masses, env.time(), 1.0 / 30.0).com_velocity;
    ASSERT_EQ(r.reward_terms[3].first, "com");
    EXPECT_NEAR(r.reward_terms[3].second, 0.10 * std::exp(-(v_ref - v_sim).squaredNorm()), 1e-9) << k;
  }
  const YamlReader bad("bad.yaml");
  EXPECT_THROW((void)make_env_factory(bad.parse("{name: tracking, com_term: speed}", "bad"), bad), Error);
}

TEST(TrackingEnv, ConfigBuildsItAndRejectsWhatDoesNotFit) {
  MIMIC_NEED_HUMANOID();
  const YamlReader reader("test.yaml");
  const EnvFactory f = make_env_factory(
      reader.parse("{name: tracking, clip: deepmimic/motions/humanoid3d_run.txt, init: fixed, max_seconds: 2,"
                   " weights: {pose: 1, velocity: 0, end_effector: 0, com: 0}}",
                   "bad"),
      reader);
  auto env = f();
  std::mt19937_64 rng(1);
  env->reset(rng);
  const StepResult r = env->step(Eigen::VectorXd::Zero(env->action_size()));
  EXPECT_GT(r.reward_terms[0].second, 0.0);
  EXPECT_EQ(r.reward_terms[1].second, 0.0);
  EXPECT_EQ(r.reward_terms[3].second, 0.0);
  // The phase is part of the default observation.
  bool phase = false;
  for (const auto& s : env->observation_layout()) phase |= s.name == "phase";
  EXPECT_TRUE(phase);
  // A dog clip on the humanoid (its file and line), an unknown key, a negative scale.
  auto message = [](const std::string& text) {
    try {
      const YamlReader bad("bad.yaml");
      (void)make_env_factory(bad.parse(text, "invalid"), bad);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("{name: tracking, clip: deepmimic/motions/dog3d_trot.txt}").find("dog3d_trot.txt:"), std::string::npos);
  EXPECT_NE(message("{name: tracking, wieghts: {pose: 1}}").find("wieghts"), std::string::npos);
  EXPECT_NE(message("{name: tracking, scales: {com: -1}}").find("scales.com"), std::string::npos);
  EXPECT_NE(message("{name: tracking, fall_height: 2}").find("fall_height"), std::string::npos);
  EXPECT_NE(message("{name: tracking, max_drift: -1}").find("max_drift"), std::string::npos);
  EXPECT_NE(message("{name: tracking, scales: {root: -1}}").find("scales.root"), std::string::npos);
  EXPECT_NE(message("{name: tracking, resync_root: often}").find("resync_root"), std::string::npos);
  // The root term is reported, weighted, once its weight is set.
  const EnvFactory rooted = make_env_factory(
      reader.parse("{name: tracking, clip: deepmimic/motions/humanoid3d_walk.txt, init: fixed, resync_root: true, weights: {root: 0.2}}", "t"),
      reader);
  auto env2 = rooted();
  env2->reset(rng);
  const StepResult r2 = env2->step(Eigen::VectorXd::Zero(env2->action_size()));
  ASSERT_EQ(r2.reward_terms.size(), 5u);
  EXPECT_EQ(r2.reward_terms[4].first, "root");
  EXPECT_GT(r2.reward_terms[4].second, 0.0);
  EXPECT_LE(r2.reward_terms[4].second, 0.2);
}
