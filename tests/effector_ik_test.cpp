// Inverse kinematics for retargeting: stance detection and holding, sliding, and the solve.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "motion/effector_ik.hpp"
#include "motion/kinematics.hpp"

using namespace mimic;

namespace {

// A leg: root, hip (spherical) at the root, knee (revolute about y) 0.4 m below, ankle 0.4 m below that.
Skeleton leg() {
  Skeleton sk;
  sk.joints.push_back(Joint{"root", -1, JointType::Free, Vec3::Zero(), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  sk.joints.push_back(Joint{"hip", 0, JointType::Spherical, Vec3::Zero(), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  sk.joints.push_back(Joint{"knee", 1, JointType::Revolute, Vec3(0, 0, -0.4), Quat::Identity(), Vec3::UnitY(), {}, 0, false});
  sk.joints.push_back(Joint{"ankle", 2, JointType::Spherical, Vec3(0, 0, -0.4), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  return sk;
}

}  // namespace

TEST(EffectorIk, StanceIsLowAndSlow) {
  // At 10 Hz: z 0, 0, 0.01, 0.2, 0 ...; x 0, 0.01, 0.02, 0.5, 1.0.
  const std::vector<Vec3> p{{0, 0, 0}, {0.01, 0, 0}, {0.02, 0, 0.01}, {0.5, 0, 0.2}, {1.0, 0, 0}};
  // Horizontal speeds by central differences: 0.1, 0.1, 2.45, 4.9, 5.0 m/s.
  const std::vector<bool> stance = stance_frames(p, 10.0, 0.05, 0.4);
  EXPECT_EQ(stance, (std::vector<bool>{true, true, false, false, false}));
  // Frame 2 is low but moving at 2.45 m/s; with a looser speed it joins.
  EXPECT_TRUE(stance_frames(p, 10.0, 0.05, 3.0)[2]);
  EXPECT_FALSE(stance_frames(p, 10.0, 0.005, 3.0)[2]);  // 1 cm above the lowest
}

TEST(EffectorIk, HeldStanceIsOnePointPerRunAndSlidesNoMore) {
  std::vector<Vec3> p{{0, 0, 0.02}, {0.02, 0.01, 0.0}, {0.04, 0.02, 0.01}, {0.5, 0, 0.3}, {1.0, 0, 0.03}, {1.02, 0, 0.02}};
  const std::vector<bool> stance{true, true, true, false, true, true};
  // Sliding before: steps 0-1 and 1-2 at 10 Hz are sqrt(0.0004 + 0.0001) * 10 = 0.2236 m/s each;
  // 4-5 is 0.02 * 10 = 0.2 m/s: mean 0.2157.
  EXPECT_NEAR(stance_sliding(p, stance, 10.0), (2 * std::sqrt(0.0005) * 10 + 0.2) / 3, 1e-12);
  hold_stance(p, stance);
  for (int f : {0, 1, 2}) EXPECT_TRUE(p[static_cast<std::size_t>(f)].isApprox(Vec3(0.02, 0.01, 0.0))) << f;
  EXPECT_TRUE(p[3].isApprox(Vec3(0.5, 0, 0.3)));  // swing untouched
  for (int f : {4, 5}) EXPECT_TRUE(p[static_cast<std::size_t>(f)].isApprox(Vec3(1.01, 0, 0.02))) << f;
  EXPECT_EQ(stance_sliding(p, stance, 10.0), 0.0);
}

TEST(EffectorIk, AReachableGoalIsMetByTheLimbWithTheRootKept) {
  const Skeleton sk = leg();
  Pose start = rest_pose(sk, Vec3(0, 0, 1.0));
  start.rot[2] = Quat(Eigen::AngleAxisd(0.1, Vec3::UnitY()));  // the knee a little bent
  std::vector<Pose> frames{start};
  // 0.657 m from the hip, inside the leg's 0.8 m reach.
  const EffectorGoal goal{3, {Vec3(0.1, 0.05, 0.35)}};
  const double left = reach_effectors(sk, frames, {goal});
  EXPECT_LT(left, 1e-3);
  const LinkFrames fk = forward_kinematics(sk, frames[0]);
  EXPECT_LT((fk.joint_pos[3] - goal.position[0]).norm(), 1e-3);
  EXPECT_LT((frames[0].root_pos - start.root_pos).norm(), 0.02);  // the limb reaches; the root barely moves
  // The knee bends the way it bent in the clip.
  EXPECT_GT(twist_angle(frames[0].rot[2], Vec3::UnitY()), 0.0);
}

TEST(EffectorIk, AGoalOutOfReachMovesTheRootAndNoKneeBendsBackwards) {
  const Skeleton sk = leg();
  Pose start = rest_pose(sk, Vec3(0, 0, 1.0));
  start.rot[2] = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY()));
  std::vector<Pose> frames{start};
  // 1.0 m below the hip: the straight leg reaches 0.8, so the root has to come down 0.2 m.
  const double left = reach_effectors(sk, frames, {EffectorGoal{3, {Vec3(0, 0, 0.0)}}});
  EXPECT_LT(left, 0.02);
  EXPECT_NEAR(frames[0].root_pos.z(), 0.8, 0.02);
  EXPECT_GE(twist_angle(frames[0].rot[2], Vec3::UnitY()), 0.0);
}

TEST(EffectorIk, BadGoalsAreErrors) {
  const Skeleton sk = leg();
  std::vector<Pose> frames{rest_pose(sk)};
  EXPECT_THROW(reach_effectors(sk, frames, {EffectorGoal{0, {Vec3::Zero()}}}), Error);             // the root is no limb
  EXPECT_THROW(reach_effectors(sk, frames, {EffectorGoal{3, {Vec3::Zero(), Vec3::Zero()}}}), Error);  // two frames for one
}
