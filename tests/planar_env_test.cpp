// Seed 000/002 validation bodies: the planar walker (Walker2d) and the 2-/3-link reacher arms.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <string>

#include "core/error.hpp"
#include "env/mjcf_env.hpp"
#include "env/planar_walker.hpp"
#include "env/reacher_arm.hpp"

using namespace mimic;
using Eigen::VectorXd;

namespace {

VectorXd vec(std::initializer_list<double> v) {
  VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

double term(const StepResult& r, const std::string& name) {
  for (const auto& [n, v] : r.reward_terms)
    if (n == name) return v;
  ADD_FAILURE() << "no reward term " << name;
  return NAN;
}

ObservationSlice slice(const Env& env, const std::string& name) {
  for (const auto& s : env.observation_layout())
    if (s.name == name) return s;
  throw Error("no slice " + name);
}

// The walker's nominal standing state with the torso at `z` (legs straight down).
VectorXd walker_qpos(double z, double angle = 0.0) {
  VectorXd q = VectorXd::Zero(9);
  q[1] = z, q[2] = angle;
  return q;
}

// Planar forward kinematics by hand: the fingertip of a chain of links turning about z.
Eigen::Vector2d arm_fk(const std::vector<double>& len, const VectorXd& q) {
  Eigen::Vector2d p(0, 0);
  double a = 0;
  for (std::size_t i = 0; i < len.size(); ++i) {
    a += q[static_cast<Eigen::Index>(i)];
    p += len[i] * Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  return p;
}

// Inverse kinematics for 2 or 3 links: for 3, the last two links act as one of length d.
VectorXd arm_ik(const std::vector<double>& len, const Eigen::Vector2d& t) {
  const double r = t.norm(), l1 = len[0];
  double d = len[1], q3 = 0, phi = 0;
  if (len.size() == 3) {
    const double l2 = len[1], l3 = len[2];
    // Any d with |l2 - l3| <= d <= l2 + l3 and |r - l1| <= d <= r + l1 works; the middle one
    // keeps both acos away from +-1 (where they lose precision).
    d = 0.5 * (std::max(std::abs(l2 - l3), std::abs(r - l1)) + std::min(l2 + l3, r + l1));
    q3 = std::acos(std::clamp((d * d - l2 * l2 - l3 * l3) / (2 * l2 * l3), -1.0, 1.0));
    phi = std::atan2(l3 * std::sin(q3), l2 + l3 * std::cos(q3));
  }
  const double q2 = std::acos(std::clamp((r * r - l1 * l1 - d * d) / (2 * l1 * d), -1.0, 1.0));
  const double q1 = std::atan2(t.y(), t.x()) - std::atan2(d * std::sin(q2), l1 + d * std::cos(q2));
  return len.size() == 3 ? vec({q1, q2 - phi, q3}) : vec({q1, q2});
}

struct BadModelEnv : MjcfEnv {
  BadModelEnv() : MjcfEnv("broken_arm", "<mujoco><worldbody><body><joint type=\"bogus\"/></body></worldbody></mujoco>", 1) {}
  int observation_size() const override { return 0; }
  std::vector<ObservationSlice> observation_layout() const override { return {}; }
  VectorXd reset(std::mt19937_64&) override { return {}; }
  StepResult step(const VectorXd&) override { return {}; }
};

}  // namespace

TEST(PlanarMjcfEnv, RejectedModelNamesTheEnvironment) {
  try {
    BadModelEnv env;
    FAIL() << "a bad model compiled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken_arm"), std::string::npos) << e.what();
  }
}

TEST(PlanarWalker, Dimensions) {
  PlanarWalkerEnv env;
  EXPECT_EQ(env.model()->nbody, 8);  // world + torso + 2 x (thigh, leg, foot)
  EXPECT_EQ(env.model()->nq, 9);
  EXPECT_EQ(env.model()->nv, 9);
  EXPECT_EQ(env.action_size(), 6);
  EXPECT_EQ(env.observation_size(), 17);  // Walker2d-v2's dim(S) (seed 002 table A.1)
  EXPECT_DOUBLE_EQ(env.control_dt(), 0.008);
  int total = 0;
  for (const auto& s : env.observation_layout()) {
    EXPECT_EQ(s.offset, total) << s.name;
    total += s.size;
  }
  EXPECT_EQ(total, 17);
  for (int a = 0; a < 6; ++a) EXPECT_DOUBLE_EQ(env.model()->actuator_gear[6 * a], 100.0);
  EXPECT_NE(planar_walker_mjcf().find("<mujoco model=\"planar_walker\">"), std::string::npos);
}

TEST(PlanarWalker, ObservationIsQposWithoutRootXAndClippedQvel) {
  PlanarWalkerEnv env;
  std::mt19937_64 rng(1);
  env.reset(rng);
  VectorXd q = walker_qpos(1.3, 0.1), v = VectorXd::LinSpaced(9, -20, 20);
  q[0] = 3.0, q[4] = -0.4;
  env.set_state(q, v);
  const VectorXd obs = env.observation();
  EXPECT_EQ(obs.head(8), q.tail(8));
  EXPECT_EQ(obs.tail(9), v.cwiseMax(-10.0).cwiseMin(10.0));
  EXPECT_EQ(obs[slice(env, "root_z").offset], 1.3);
  EXPECT_EQ(obs[slice(env, "joint_pos").offset + 1], -0.4);  // qpos[4]: the right knee
}

TEST(PlanarWalker, RewardHandCheckedInFlight) {
  PlanarWalkerEnv env;
  std::mt19937_64 rng(2);
  env.reset(rng);
  // In the air (feet 0.35 m above the floor), v_x = 0.5, no action: the body translates rigidly.
  VectorXd v = VectorXd::Zero(9);
  v[0] = 0.5;
  env.set_state(walker_qpos(1.6), v);
  StepResult r = env.step(VectorXd::Zero(6));
  EXPECT_NEAR(term(r, "forward"), 0.5, 1e-9);
  EXPECT_NEAR(r.reward(), 1.0 + 0.5, 1e-9);
  EXPECT_EQ(r.termination, Termination::None);
  // With an action: alive 1, control -1e-3 |u|^2, forward = root x displacement / 8 ms.
  env.set_state(walker_qpos(1.6), v);
  const VectorXd u = vec({0.5, -0.3, 1.0, 0.0, 0.2, -1.0});
  r = env.step(u);
  EXPECT_EQ(term(r, "alive"), 1.0);
  EXPECT_NEAR(term(r, "control"), -1e-3 * (0.25 + 0.09 + 1.0 + 0.04 + 1.0), 1e-15);
  EXPECT_NEAR(term(r, "forward"), env.qpos()[0] / 0.008, 1e-9);
  EXPECT_NEAR(r.reward(), 1.0 + env.qpos()[0] / 0.008 - 2.38e-3, 1e-9);
}

TEST(PlanarWalker, ActionsAreClippedToCtrlRange) {
  PlanarWalkerEnv a, b;
  std::mt19937_64 ra(3), rb(3);
  a.reset(ra), b.reset(rb);
  const StepResult big = a.step(vec({3, -2, 1.5, -9, 0.5, 4}));
  const StepResult clipped = b.step(vec({1, -1, 1, -1, 0.5, 1}));
  EXPECT_EQ(big.observation, clipped.observation);
  EXPECT_NEAR(term(big, "control"), -1e-3 * 5.25, 1e-15);
  EXPECT_THROW(a.step(VectorXd::Zero(5)), Error);
  EXPECT_THROW(a.step(vec({0, 0, NAN, 0, 0, 0})), Error);
}

TEST(PlanarWalker, FallRulesAndNotAtTheInitialState) {
  PlanarWalkerEnv env;
  std::mt19937_64 rng(4);
  env.reset(rng);
  EXPECT_EQ(env.fall_check(), Termination::None);
  EXPECT_EQ(env.step(VectorXd::Zero(6)).termination, Termination::None);
  // Torso at 0.7 m with both legs folded up behind it (nothing touches the floor): height rule.
  VectorXd q = walker_qpos(0.7);
  q[3] = q[6] = -2.5;
  env.set_state(q, VectorXd::Zero(9));
  EXPECT_EQ(env.step(VectorXd::Zero(6)).termination, Termination::Fall);
  EXPECT_LT(env.torso_height(), 0.8);
  env.set_state(walker_qpos(2.1), VectorXd::Zero(9));  // too high
  EXPECT_EQ(env.step(VectorXd::Zero(6)).termination, Termination::Fall);
  env.set_state(walker_qpos(1.25, 1.2), VectorXd::Zero(9));  // pitched beyond 1 rad
  EXPECT_EQ(env.step(VectorXd::Zero(6)).termination, Termination::Fall);
  env.set_state(walker_qpos(1.25, -0.9), VectorXd::Zero(9));
  EXPECT_EQ(env.fall_check(), Termination::None);
}

TEST(PlanarWalker, TimeLimitIsNotAFall) {
  PlanarWalkerConfig cfg;
  cfg.max_steps = 5;
  PlanarWalkerEnv env(cfg);
  std::mt19937_64 rng(5);
  env.reset(rng);
  for (int t = 1; t <= 5; ++t) {
    const StepResult r = env.step(VectorXd::Zero(6));
    EXPECT_EQ(r.termination, t < 5 ? Termination::None : Termination::TimeLimit) << "step " << t;
    EXPECT_FALSE(is_failure(r.termination));
  }
  env.reset(rng);  // a fresh episode counts again
  for (int t = 1; t < 5; ++t) EXPECT_EQ(env.step(VectorXd::Zero(6)).termination, Termination::None);
  // A fall on the last step is still a failure.
  env.set_state(walker_qpos(2.1), VectorXd::Zero(9));
  EXPECT_EQ(env.step(VectorXd::Zero(6)).termination, Termination::Fall);
}

TEST(PlanarWalker, ZeroActionFallsWithinSeconds) {
  PlanarWalkerEnv env;
  std::mt19937_64 rng(6);
  env.reset(rng);
  int fell_at = -1;
  for (int t = 1; t <= 1000 && fell_at < 0; ++t)
    if (env.step(VectorXd::Zero(6)).termination == Termination::Fall) fell_at = t;
  EXPECT_GT(fell_at, 10);    // not at once: it starts upright
  EXPECT_LE(fell_at, 400);   // 3.2 s (it falls after ~0.9-1.8 s): it cannot stand passively
}

TEST(PlanarWalker, ResetNoiseIsSmallAndDeterministic) {
  PlanarWalkerEnv a, b;
  std::mt19937_64 ra(7), rb(7), rc(8);
  const VectorXd oa = a.reset(ra), ob = b.reset(rb);
  EXPECT_EQ(oa, ob);
  VectorXd nominal = VectorXd::Zero(17);
  nominal[0] = 1.25;
  EXPECT_LE((oa - nominal).cwiseAbs().maxCoeff(), 0.005);
  EXPECT_GT((oa - nominal).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_NE(a.reset(rc), oa);
  // Same seed and actions -> bitwise identical trajectories.
  a.reset(ra = std::mt19937_64(9)), b.reset(rb = std::mt19937_64(9));
  std::mt19937_64 actions(10);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int t = 0; t < 200; ++t) {
    VectorXd act(6);
    for (Eigen::Index i = 0; i < 6; ++i) act[i] = u(actions);
    const StepResult sa = a.step(act), sb = b.step(act);
    ASSERT_EQ(sa.observation, sb.observation) << "step " << t;
    ASSERT_EQ(sa.reward(), sb.reward());
    if (sa.done()) break;
  }
}

TEST(PlanarWalker, MisuseAndDivergenceAreErrors) {
  PlanarWalkerEnv env;
  EXPECT_THROW(env.step(VectorXd::Zero(6)), Error);  // before reset
  std::mt19937_64 rng(19);
  env.reset(rng);
  EXPECT_THROW(env.set_state(VectorXd::Zero(8), VectorXd::Zero(9)), Error);
  // MuJoCo would silently reset a blown-up state; the environment says so. (A handler keeps
  // MuJoCo from writing its warning to MUJOCO_LOG.TXT in the working directory.)
  static int warnings = 0;
  auto* const previous = mju_user_warning;
  mju_user_warning = [](const char*) { ++warnings; };
  env.set_state(walker_qpos(1.25), VectorXd::Constant(9, 1e11));
  EXPECT_THROW(env.step(VectorXd::Zero(6)), Error);
  mju_user_warning = previous;
  EXPECT_EQ(warnings, 1);
}

TEST(ReacherArm, Dimensions) {
  ReacherArmEnv two, three(ReacherConfig::three_link());
  EXPECT_EQ(two.model()->nq, 2);
  EXPECT_EQ(two.action_size(), 2);
  EXPECT_EQ(two.observation_size(), 12);
  EXPECT_EQ(three.model()->nq, 3);
  EXPECT_EQ(three.action_size(), 3);
  EXPECT_EQ(three.observation_size(), 15);
  EXPECT_EQ(slice(three, "ee_to_target").offset, 13);
  EXPECT_EQ(two.target_period_steps(), 50);  // 1 s at 50 Hz
  ReacherConfig cfg;
  cfg.observation = "ee_to_target";
  ReacherArmEnv partial(cfg);
  EXPECT_EQ(partial.observation_size(), 2);
  ASSERT_EQ(partial.observation_layout().size(), 1u);
  cfg.observation = "joint_angles";
  EXPECT_THROW(ReacherArmEnv{cfg}, Error);
  cfg.observation = "full";
  cfg.timestep = 0;
  EXPECT_THROW(ReacherArmEnv{cfg}, Error);
}

TEST(ReacherArm, FingertipMatchesHandForwardKinematics) {
  for (const ReacherConfig& cfg : {ReacherConfig::two_link(), ReacherConfig::three_link()}) {
    ReacherArmEnv env(cfg);
    std::mt19937_64 rng(11);
    env.reset(rng);
    const VectorXd q = cfg.link_lengths.size() == 2 ? vec({0.3, -1.1}) : vec({2.0, -0.7, 1.9});
    env.set_state(q, VectorXd::Zero(q.size()));
    const Eigen::Vector2d hand = arm_fk(cfg.link_lengths, q);
    EXPECT_NEAR((env.fingertip() - hand).norm(), 0.0, 1e-12);
    // The 2-link case written out: l1 (cos q1, sin q1) + l2 (cos(q1+q2), sin(q1+q2)).
    if (q.size() == 2) {
      EXPECT_NEAR(env.fingertip().x(), 0.1 * std::cos(0.3) + 0.11 * std::cos(-0.8), 1e-12);
    }
  }
}

TEST(ReacherArm, EeToTargetIsTargetMinusFingertip) {
  ReacherConfig cfg;
  ReacherArmEnv full(cfg);
  cfg.observation = "ee_to_target";
  ReacherArmEnv partial(cfg);
  std::mt19937_64 ra(12), rb(12);
  full.reset(ra), partial.reset(rb);
  for (int t = 0; t < 60; ++t) {  // across a target change
    const StepResult f = full.step(vec({0.4, -0.2})), p = partial.step(vec({0.4, -0.2}));
    const ObservationSlice s = slice(full, "ee_to_target");
    const Eigen::Vector2d expected = full.target() - arm_fk(cfg.link_lengths, full.qpos());
    EXPECT_NEAR((f.observation.segment(s.offset, 2) - expected).norm(), 0.0, 1e-12);
    EXPECT_EQ(p.observation, f.observation.segment(s.offset, 2));
    EXPECT_EQ(f.observation.segment(slice(full, "target").offset, 2), full.target());
  }
}

TEST(ReacherArm, TargetMovesEverySecondWithinTheAnnulus) {
  ReacherArmEnv env;
  std::mt19937_64 rng(13);
  env.reset(rng);
  int changes = 0;
  for (int t = 1; t <= 200; ++t) {
    const Eigen::Vector2d before = env.target();
    const StepResult r = env.step(VectorXd::Zero(2));
    const bool moved = env.target() != before;
    EXPECT_EQ(moved, t % 50 == 0) << "step " << t;
    changes += moved;
    EXPECT_GE(env.target().norm(), 0.05 - 1e-12);
    EXPECT_LE(env.target().norm(), 0.20 + 1e-12);
    EXPECT_EQ(r.termination, t < 200 ? Termination::None : Termination::TimeLimit);
  }
  EXPECT_EQ(changes, 4);
}

TEST(ReacherArm, ThreeLinkReachesTheTwoLinkAnnulus) {
  const auto [in2, out2] = reach_annulus(ReacherConfig::two_link().link_lengths);
  const auto [in3, out3] = reach_annulus(ReacherConfig::three_link().link_lengths);
  EXPECT_NEAR(out2, out3, 1e-12);
  EXPECT_NEAR(in2, 0.01, 1e-12);
  EXPECT_EQ(in3, 0.0);
  // Every target either arm draws is reached by MuJoCo's fingertip at the hand-computed IK pose.
  for (const ReacherConfig& cfg : {ReacherConfig::two_link(), ReacherConfig::three_link()}) {
    ReacherArmEnv env(cfg);
    std::mt19937_64 rng(14);
    for (int i = 0; i < 100; ++i) {
      env.reset(rng);
      const VectorXd q = arm_ik(cfg.link_lengths, env.target());
      env.set_state(q, VectorXd::Zero(q.size()));
      ASSERT_NEAR((env.fingertip() - env.target()).norm(), 0.0, 1e-9) << cfg.link_lengths.size() << " links, target " << i;
    }
  }
  ReacherConfig bad = ReacherConfig::three_link();
  bad.link_lengths = {0.05, 0.05, 0.2};  // cannot reach closer than 0.1 m
  EXPECT_THROW(ReacherArmEnv{bad}, Error);
}

TEST(ReacherArm, RewardAndClippedActions) {
  ReacherConfig cfg;
  ReacherArmEnv a(cfg), b(cfg);
  std::mt19937_64 ra(15), rb(15);
  a.reset(ra), b.reset(rb);
  const StepResult big = a.step(vec({5, -7})), unit = b.step(vec({1, -1}));
  EXPECT_EQ(big.observation, unit.observation);
  EXPECT_DOUBLE_EQ(term(big, "control"), -2.0);
  EXPECT_NEAR(term(big, "reach"), -(a.target() - a.fingertip()).norm(), 1e-15);
  cfg.squared_distance = true;
  ReacherArmEnv sq(cfg);
  std::mt19937_64 rc(15);
  sq.reset(rc);
  const StepResult r = sq.step(vec({1, -1}));
  EXPECT_NEAR(term(r, "reach"), -std::pow(term(unit, "reach"), 2), 1e-15);
}

TEST(ReacherArm, SameSeedSameTrajectory) {
  ReacherArmEnv a(ReacherConfig::three_link()), b(ReacherConfig::three_link());
  std::mt19937_64 ra(16), rb(16), rc(17);
  EXPECT_EQ(a.reset(ra), b.reset(rb));
  const Eigen::Vector2d first_target = a.target();
  std::mt19937_64 actions(18);
  std::normal_distribution<double> u(0, 0.7);
  for (int t = 0; t < 200; ++t) {
    const VectorXd act = vec({u(actions), u(actions), u(actions)});
    const StepResult sa = a.step(act), sb = b.step(act);
    ASSERT_EQ(sa.observation, sb.observation) << "step " << t;
    ASSERT_EQ(sa.reward(), sb.reward());
  }
  // The targets, drawn during the episode, also follow reset()'s rng only.
  const VectorXd first = a.reset(ra = std::mt19937_64(16));
  EXPECT_EQ(a.target(), first_target);
  EXPECT_NE(b.reset(rc), first);
  EXPECT_NE(b.target(), first_target);
}
