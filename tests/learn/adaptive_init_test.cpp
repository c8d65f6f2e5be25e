// Adaptive state initialisation (seed 003): the initial spread from the clip's sample std, states
// drawn around the reference at fixed phases, the gradient step moving the means toward high
// returns on a toy return function, episode returns recorded by the wrapper, and the trainer
// saving the distribution with its checkpoint.
#include "learn/imitation/adaptive_init.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "env/tracking.hpp"
#include "learn/trainer/trainer_impl.hpp"
#include "../humanoid_data.hpp"
#include "trainer_access.hpp"

using namespace mimic;

namespace {

// root (free) -> arm (spherical, 1 m along x) -> hand (fixed); the arm turns 0.2 rad about z per
// frame at 10 fps: 0, 0.2, 0.4.
std::shared_ptr<const Clip> arm_clip() {
  Clip c;
  c.name = "arm";
  auto add = [&](const char* name, int parent, JointType type) {
    Joint j;
    j.name = name, j.parent = parent, j.type = type, j.offset = parent < 0 ? Vec3::Zero() : Vec3(1, 0, 0);
    c.skeleton.joints.push_back(j);
  };
  add("root", -1, JointType::Free);
  add("arm", 0, JointType::Spherical);
  add("hand", 1, JointType::Fixed);
  c.fps = 10;
  for (int f = 0; f < 3; ++f) {
    Pose p = rest_pose(c.skeleton, Vec3(0, 0, 1));
    p.rot[1] = Quat(Eigen::AngleAxisd(0.2 * f, Vec3::UnitZ()));
    c.frames.push_back(p);
  }
  return std::make_shared<const Clip>(std::move(c));
}

constexpr int kArmZ = 1 + 3 + 2;  // root height, root rotation (3), arm rotation x y z

}  // namespace

TEST(AdaptiveInit, SpreadStartsAtTheClipsSampleStd) {
  const auto clip = arm_clip();
  AdaptiveInitConfig cfg;
  cfg.components = 3;
  const AdaptiveInit asi(clip, clip->skeleton, cfg);
  // 1 + 3 (root) + 3 (arm) rotations, 3 + 3 (root) + 3 (arm) velocities; the fixed hand has none.
  ASSERT_EQ(asi.dims(), 16);
  EXPECT_NEAR(asi.initial_std()[kArmZ], 0.2, 1e-12);  // sample std of {0, 0.2, 0.4}
  EXPECT_NEAR(asi.initial_std()[0], cfg.min_std, 1e-15);  // the root never moves: the floor
  EXPECT_NEAR(asi.initial_std()[kArmZ + 9], cfg.min_std, 1e-9);  // a constant 2 rad/s
  EXPECT_TRUE(asi.means().isZero());
  EXPECT_NEAR(asi.phase_time(1), 0.2 / 3, 1e-12);
  cfg.std_scale = 0.5;
  EXPECT_NEAR(AdaptiveInit(clip, clip->skeleton, cfg).initial_std()[kArmZ], 0.1, 1e-12);
  cfg.components = 0;
  EXPECT_THROW(AdaptiveInit(clip, clip->skeleton, cfg), Error);
}

TEST(AdaptiveInit, OffsetsApplyToTheReferenceStateAtTheComponentsPhase) {
  const auto clip = arm_clip();
  AdaptiveInitConfig cfg;
  cfg.components = 2;
  const AdaptiveInit asi(clip, clip->skeleton, cfg);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(asi.dims());
  const InitState ref = init_state_from_clip(*clip, 0.1);
  const InitState same = asi.state(1, x);  // component 1 of 2: half the 0.2 s clip
  EXPECT_DOUBLE_EQ(same.time, 0.1);
  EXPECT_LT(rotation_distance(same.pose.rot[1], ref.pose.rot[1]), 1e-12);
  x[0] = 0.05;
  x[kArmZ] = 0.3;
  x[kArmZ + 9] = -1.0;
  const InitState moved = asi.state(1, x);
  EXPECT_NEAR(moved.pose.root_pos.z(), ref.pose.root_pos.z() + 0.05, 1e-12);
  EXPECT_NEAR(rotation_distance(moved.pose.rot[1], ref.pose.rot[1]), 0.3, 1e-12);
  EXPECT_NEAR(moved.velocity.joint_ang[1].z(), ref.velocity.joint_ang[1].z() - 1.0, 1e-12);
  EXPECT_THROW(asi.state(0, Eigen::VectorXd::Zero(3)), Error);
}

TEST(AdaptiveInit, DrawsAreGaussianAroundTheMeansOverEvenlyUsedComponents) {
  const auto clip = arm_clip();
  AdaptiveInitConfig cfg;
  cfg.components = 4;
  const AdaptiveInit asi(clip, clip->skeleton, cfg);
  std::mt19937_64 rng(5);
  std::vector<int> count(4, 0);
  double sum = 0, sum2 = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const AdaptiveInit::Draw d = asi.draw(rng);
    ++count[static_cast<std::size_t>(d.component)];
    sum += d.x[kArmZ], sum2 += d.x[kArmZ] * d.x[kArmZ];
  }
  for (int c : count) EXPECT_NEAR(c, n / 4, 300);
  EXPECT_NEAR(sum / n, 0.0, 0.01);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.2, 0.01);
}

TEST(AdaptiveInit, GradientStepsMoveTheMeansTowardHighReturns) {
  // A toy return that only the arm's z offset decides, best at +0.3: R = -(x - 0.3)^2.
  const auto clip = arm_clip();
  AdaptiveInitConfig cfg;
  cfg.components = 3;
  cfg.step = 2.0;
  AdaptiveInit asi(clip, clip->skeleton, cfg);
  std::mt19937_64 rng(9);
  const double other_std = std::exp(asi.log_std()(0, 1));
  for (int step = 0; step < 300; ++step) {
    std::vector<AdaptiveInit::Outcome> batch;
    for (int i = 0; i < 300; ++i) {
      const AdaptiveInit::Draw d = asi.draw(rng);
      batch.push_back({d.component, d.x, -(d.x[kArmZ] - 0.3) * (d.x[kArmZ] - 0.3)});
    }
    asi.update(batch);
  }
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(asi.means()(c, kArmZ), 0.2) << "component " << c;
    EXPECT_LT(asi.means()(c, kArmZ), 0.4) << "component " << c;
    EXPECT_LT(std::exp(asi.log_std()(c, kArmZ)), 0.8 * 0.2) << "a peaked return narrows the spread";
    // A dimension the return ignores stays where it was (its gradient is noise).
    EXPECT_NEAR(asi.means()(c, 1), 0.0, 0.05 * other_std + 1e-3);
  }
  // A component with one episode in the batch is left alone (its baseline is its own return).
  const Eigen::MatrixXd before = asi.means();
  asi.update({{0, Eigen::VectorXd::Constant(asi.dims(), 1.0), 5.0}});
  EXPECT_TRUE(asi.means().isApprox(before));
}

TEST(AdaptiveInit, WrapperRecordsEachEpisodesDiscountedReturn) {
  MIMIC_NEED_HUMANOID();
  const CharacterModel ch = test::humanoid3d();
  const auto walk = test::humanoid3d_motion(ch, "humanoid3d_walk.txt");
  TrackingConfig tc;
  tc.env.max_seconds = 0.5;
  AdaptiveInitConfig cfg;
  cfg.components = 5;
  cfg.std_scale = 0.1;
  auto dist = std::make_shared<const AdaptiveInit>(walk, ch.skeleton, cfg);
  AdaptiveInitEnv env(make_tracking_env(ch, walk, tc), dist, 0.9);
  std::mt19937_64 rng(2);
  env.reset(rng);
  double expected = 0, discount = 1;
  StepResult r;
  do {
    r = env.step(Eigen::VectorXd::Zero(env.action_size()));
    expected += discount * r.reward();
    discount *= 0.9;
  } while (!r.done());
  const auto outcomes = env.take_outcomes();
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_NEAR(outcomes[0].ret, expected, 1e-12);
  EXPECT_EQ(outcomes[0].x.size(), dist->dims());
  EXPECT_TRUE(env.take_outcomes().empty());
  EXPECT_THROW(AdaptiveInitEnv(std::make_unique<AdaptiveInitEnv>(make_tracking_env(ch, walk, tc), dist, 0.9), dist, 0.9), Error);
}

TEST(AdaptiveInit, TrainerStepsItAndAResumedRunContinuesExactly) {
  MIMIC_NEED_HUMANOID();
  const std::string text =
      "seed: 3\niterations: 4\ncheckpoint_every: 2\nenv: {name: tracking, max_seconds: 0.3}\ncollect: {envs: 4, samples: 64}\n"
      "policy: {hidden: [8]}\nvalue: {hidden: [8]}\nppo: {epochs: 1, value_epochs: 1}\n"
      "init: {kind: adaptive, components: 3, episodes: 6, step: 0.5}\n";
  const auto dir = test::temp_dir("asi_resume");
  auto init_metrics = [](const IterationMetrics& m) {
    return std::vector<double>{m.get("init_updates"), m.get("init_mean_shift"), m.get("init_std_ratio"), m.get("return")};
  };
  std::vector<std::vector<double>> straight, resumed;
  Eigen::MatrixXd straight_means;
  {
    TrainOptions o;
    o.run_dir = dir / "straight";
    Trainer t(parse_train_config(text, "asi.yaml"), o);
    for (int i = 0; i < 4; ++i) straight.push_back(init_metrics(t.iterate()));
    straight_means = impl_of(t).adaptive_init->means();
  }
  EXPECT_GE(straight.back()[0], 2.0);  // gradient steps were taken
  EXPECT_GT(straight.back()[1], 0.0);  // and moved the means
  {
    TrainOptions o;
    o.run_dir = dir / "halves";
    Trainer t(parse_train_config(text, "asi.yaml"), o);
    for (int i = 0; i < 2; ++i) resumed.push_back(init_metrics(t.iterate()));
  }
  TrainOptions o;
  o.run_dir = dir / "halves";
  o.resume = true;
  Trainer t(parse_train_config(text, "asi.yaml"), o);
  for (int i = 0; i < 2; ++i) resumed.push_back(init_metrics(t.iterate()));
  EXPECT_EQ(resumed, straight);
  EXPECT_EQ(impl_of(t).adaptive_init->means(), straight_means);
  // A walker has no clip to start from.
  EXPECT_THROW(Trainer(parse_train_config("env: {name: planar_walker}\ninit: {kind: adaptive}\n", "w.yaml")), Error);
}
