// The motion-matching baseline's pose comparison (control/pose_matching), pinned on a hand-made
// two-joint skeleton, and the switch rule that uses it on the committed walk.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "control/pose_matching.hpp"
#include "error_message.hpp"
#include "mimic/runtime.hpp"
#include "test_data.hpp"

using namespace mimic;

namespace {

// A root (free) at 1 m and an arm 1 m along the root's X.
Clip two_joint_clip() {
  Clip c;
  Joint root, arm;
  root.name = "root", root.type = JointType::Free;
  arm.name = "arm", arm.parent = 0, arm.offset = Vec3(1, 0, 0);
  c.skeleton.joints = {root, arm};
  return c;
}

Pose pitched(double deg, const Vec3& root = Vec3(0, 0, 1), double yaw_deg = 0) {
  Pose p;
  p.root_pos = root;
  p.rot = {Quat(Eigen::AngleAxisd(yaw_deg * std::numbers::pi / 180, Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(deg * std::numbers::pi / 180, Vec3::UnitY())),
           Quat::Identity()};
  return p;
}

TEST(PoseMatcher, NearestFrameInTheHeadingFrameOverTheClipsSpreadPinnedByHand) {
  // Frame A: the arm level at (1, 0, 1). Frame B: the root pitched 60 degrees, the arm at
  // (0.5, 0, 1 - 0.866). Their mean arm is 0.5 m from either, the roots coincide: the spread (mean
  // joint distance from the mean pose) is (0 + 0.5) / 2 = 0.25 m.
  Clip clip = two_joint_clip();
  clip.frames = {pitched(0), pitched(60)};
  const PoseMatcher m({&clip});
  EXPECT_NEAR(m.spread(), 0.25, 1e-12);
  // Frame A moved 5 m away and turned 90 degrees about the vertical: the same pose.
  EXPECT_NEAR(m.cost(pitched(0, Vec3(3, 4, 1), 90)), 0.0, 1e-12);
  EXPECT_NEAR(m.readiness(pitched(60, Vec3(-2, 1, 1), -45)), 1.0, 1e-12);
  // Halfway, pitched 30 degrees: the arm is 2 sin 15 deg from either frame's, the root 0 from both,
  // so the cost is sin 15 deg and the readiness 1 - sin 15 / 0.25.
  const double s15 = std::sin(15 * std::numbers::pi / 180);
  EXPECT_NEAR(m.cost(pitched(30)), s15, 1e-12);
  EXPECT_NEAR(m.readiness(pitched(30)), 1 - s15 / 0.25, 1e-12);
  // Raised by 0.1 m: both joints 0.1 m from frame A.
  EXPECT_NEAR(m.cost(pitched(0, Vec3(0, 0, 1.1))), 0.1, 1e-12);
  EXPECT_THROW(PoseMatcher({}), Error);
}

TEST(PoseMatcher, NearestNamesTheClipAndFrameAndRefusesAnotherSkeleton) {
  // Clip 0: pitched 0 and 60 degrees; clip 1: pitched 20 and 40. Pitched 35 is nearest to clip 1's
  // frame 1 (arm 2 sin 2.5 deg away, against 2 sin 7.5 and more), pitched 55 to clip 0's frame 1.
  Clip a = two_joint_clip(), b = two_joint_clip();
  a.frames = {pitched(0), pitched(60)};
  b.frames = {pitched(20), pitched(40)};
  const PoseMatcher m({&a, &b});
  const FrameMatch near35 = m.nearest(pitched(35, Vec3(1, 1, 1), 30));
  EXPECT_EQ(near35.clip, 1);
  EXPECT_EQ(near35.frame, 1);
  EXPECT_NEAR(near35.distance, std::sin(2.5 * std::numbers::pi / 180), 1e-12);  // (0 + 2 sin 2.5 deg) / 2 joints
  const FrameMatch near55 = m.nearest(pitched(55));
  EXPECT_EQ(near55.clip, 0);
  EXPECT_EQ(near55.frame, 1);
  Pose three = pitched(0);
  three.rot.push_back(Quat::Identity());
  EXPECT_NE(test::error_of([&] { (void)m.nearest(three); }).find("a pose of 3 joints against clips of 2"), std::string::npos);
}

TEST(PoseMatcher, TheWalksOwnStartMatchesItsClipAndTheRuleSwitchesOnlyAtAReadinessReached) {
  std::filesystem::path data;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", data);
  const std::filesystem::path models = std::filesystem::path(MIMIC_SOURCE_DIR) / "models";
  const auto walk = Skill::load(models / "humanoid_walk_iccgan", "walk");
  const auto run = Skill::load(models / "humanoid_run_iccgan_straight_loop", "run");
  Controller c({walk, run}, 2);
  // A start drawn from the walk's clip (before any step) is one of its frames, or between two.
  EXPECT_GT(c.matching("walk"), 0.8);
  // The walk's pose is farther from the run's frames than from its own.
  EXPECT_LT(c.matching("run"), c.matching("walk"));
  SwitchRule r;
  r.by = SwitchRule::By::Matching;
  r.threshold = 1.01;  // above any readiness: never
  r.time_limit_seconds = 0.2;
  c.set_switch_rule(r);
  c.request("run");
  std::string dropped;
  for (int i = 0; i < 10 && dropped.empty(); ++i) dropped = c.step().dropped;
  EXPECT_EQ(dropped, "run");
  EXPECT_EQ(c.skill(), "walk");
  r.threshold = -100;  // any pose
  c.set_switch_rule(r);
  c.request("run");
  EXPECT_EQ(c.step().switched_to, "run");
}

}  // namespace
