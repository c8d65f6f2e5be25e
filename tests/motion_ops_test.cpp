// Resampling, mirroring, velocities and the heading frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "error_message.hpp"
#include "motion/bvh.hpp"
#include "motion/deepmimic.hpp"
#include "motion/kinematics.hpp"
#include "motion/mirror.hpp"
#include "motion/resample.hpp"
#include "test_data.hpp"

using namespace mimic;

namespace {

// A two-link chain: root -> left_leg (spherical) and right_leg (spherical), mirror images.
Skeleton tiny_skeleton() {
  Skeleton sk;
  sk.joints.push_back(Joint{"root", -1, JointType::Free, Vec3::Zero(), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  sk.joints.push_back(Joint{"left_leg", 0, JointType::Spherical, Vec3(0, 0.1, 0), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  sk.joints.push_back(Joint{"right_leg", 0, JointType::Spherical, Vec3(0, -0.1, 0), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  sk.sites.push_back(Site{"left_foot", 1, Vec3(0, 0, -0.5)});
  sk.sites.push_back(Site{"right_foot", 2, Vec3(0, 0, -0.5)});
  return sk;
}

Clip load_walk() {
  const auto dir = test::shared_data();
  const Skeleton sk = load_deepmimic_character(dir / "deepmimic/characters/humanoid3d.txt").skeleton;
  return load_deepmimic_motion(dir / "deepmimic/motions/humanoid3d_walk.txt", sk);
}

double max_pose_difference(const Clip& a, const Clip& b) {
  double worst = 0;
  for (std::size_t f = 0; f < a.frames.size(); ++f) {
    worst = std::max(worst, (a.frames[f].root_pos - b.frames[f].root_pos).norm());
    for (std::size_t j = 0; j < a.frames[f].rot.size(); ++j)
      worst = std::max(worst, rotation_distance(a.frames[f].rot[j], b.frames[f].rot[j]));
  }
  return worst;
}

// "ten": 11 frames at 10 Hz, one looping second, the root at x = t.
Clip one_second_clip() {
  Clip c;
  c.name = "ten";
  c.skeleton = tiny_skeleton();
  c.fps = 10;
  c.loop = LoopMode::Wrap;
  for (int i = 0; i < 11; ++i) c.frames.push_back(rest_pose(c.skeleton, Vec3(0.1 * i, 0, 1)));
  return c;
}

}  // namespace

TEST(Resample, LinearRootMotionIsReproducedExactly) {
  Clip c;
  c.skeleton = tiny_skeleton();
  c.fps = 10;
  for (int i = 0; i < 5; ++i) {
    Pose p = rest_pose(c.skeleton, Vec3(0.3 * i, 0, 1));
    p.rot[1] = axis_rotation('y', 0.2 * i);
    c.frames.push_back(p);
  }
  const Clip up = resample(c, 40);
  ASSERT_EQ(up.num_frames(), 17);
  EXPECT_DOUBLE_EQ(up.fps, 40);
  // Frame 3 at t = 0.075 s: x = 0.3 * 0.75 = 0.225 (Catmull-Rom is exact on lines), the leg
  // turned by 0.2 * 0.75 = 0.15 rad (slerp is exact on a constant spin).
  EXPECT_NEAR(up.frames[3].root_pos.x(), 0.225, 1e-12);
  EXPECT_NEAR(twist_angle(up.frames[3].rot[1], Vec3::UnitY()), 0.15, 1e-12);
  EXPECT_NEAR(up.duration(), c.duration(), 1e-12);
}

TEST(Resample, UpThenDownReturnsTheOriginalFrames) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", p);
  const Clip walk = load_walk();
  const Clip up = resample(walk, 120);
  EXPECT_EQ(up.num_frames(), 4 * (walk.num_frames() - 1) + 1);
  EXPECT_NEAR(up.duration(), walk.duration(), 1e-9);  // a wrap clip keeps its exact cycle
  const Clip down = resample(up, walk.fps);
  ASSERT_EQ(down.num_frames(), walk.num_frames());
  EXPECT_LT(max_pose_difference(walk, down), 1e-9);
}

TEST(Resample, CmuDownAndUpStaysWithinStatedError) {
  std::filesystem::path path;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", path);
  const Clip orig = load_bvh(path, AxisConvention{"y", "z", 0.056444});
  // 120 Hz -> 30 Hz (seed 000's rate) -> 120 Hz: link positions stay within 1 cm on average,
  // 5 cm at worst (fast hand motion loses detail at 30 Hz).
  const Clip back = resample(resample(orig, 30), orig.fps);
  const int n = std::min(orig.num_frames(), back.num_frames());
  ASSERT_GT(n, 980);
  double sum = 0, worst = 0;
  long count = 0;
  LinkFrames a, b;
  for (int f = 0; f < n; ++f) {
    forward_kinematics(orig.skeleton, orig.frames[static_cast<std::size_t>(f)], a);
    forward_kinematics(back.skeleton, back.frames[static_cast<std::size_t>(f)], b);
    for (std::size_t j = 0; j < a.joint_pos.size(); ++j) {
      const double e = (a.joint_pos[j] - b.joint_pos[j]).norm();
      sum += e;
      worst = std::max(worst, e);
      ++count;
    }
  }
  EXPECT_LT(sum / static_cast<double>(count), 0.01);
  EXPECT_LT(worst, 0.05);
}

TEST(Resample, IrregularDeepMimicFramesAreMadeUniform) {
  std::filesystem::path ch, path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_roll.txt", path);
  // humanoid3d_roll.txt: 120 durations, one of them 0.032666 instead of 0.016666.
  const Clip roll = load_deepmimic_motion(path, load_deepmimic_character(ch).skeleton);
  const double total = 119 * 0.016666 + 0.032666;
  EXPECT_NEAR(roll.duration(), total, 1e-9);
  EXPECT_EQ(roll.num_frames(), 122);
  EXPECT_NEAR(roll.fps, 1.0 / 0.016666, 0.05);  // adjusted so whole frames span the duration
}

TEST(Excerpt, KeepsTheFramesWithinTheStretchAndDoesNotLoop) {
  const Clip c = one_second_clip();
  // 0.25 to 0.6 s: the frames at 0.3, 0.4, 0.5 and 0.6 s.
  const Clip e = excerpt(c, 0.25, 0.6);
  ASSERT_EQ(e.num_frames(), 4);
  EXPECT_DOUBLE_EQ(e.frames.front().root_pos.x(), 0.1 * 3);
  EXPECT_DOUBLE_EQ(e.frames.back().root_pos.x(), 0.1 * 6);
  EXPECT_DOUBLE_EQ(e.fps, 10);
  EXPECT_EQ(e.loop, LoopMode::None);
  EXPECT_EQ(e.name, "ten");
  // Bounds on frames are kept (0.3 s is frame 3 despite 0.3 * 10 = 2.9999...), the whole clip too.
  EXPECT_EQ(excerpt(c, 0.3, 0.5).num_frames(), 3);
  EXPECT_EQ(excerpt(c, 0.0, 1.0).num_frames(), 11);
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{{-0.1, 0.5}, {0.5, 1.2}, {0.6, 0.6}, {0.7, 0.2}})
    EXPECT_NE(test::error_of([&] { (void)excerpt(c, a, b); }).find("is not a stretch of its 1.000 s"), std::string::npos) << a << " " << b;
  EXPECT_NE(test::error_of([&] { (void)excerpt(c, 0.31, 0.39); }).find("fewer than two of its frames (at 10.000 Hz)"), std::string::npos);
  EXPECT_NE(test::error_of([&] { (void)excerpt(c, 0.31, 0.39); }).find("clip 'ten'"), std::string::npos);
}

TEST(ClipStretch, ParsesFileFromAndToAndCountsNegativeTimesFromTheEnd) {
  const ClipStretch whole = parse_clip_stretch("walk.txt");
  EXPECT_TRUE(whole.whole);
  EXPECT_EQ(whole.file, "walk.txt");
  const ClipStretch last = parse_clip_stretch("dir/a@b.txt@-0.3");  // split at the last '@'
  EXPECT_EQ(last.file, "dir/a@b.txt");
  EXPECT_FALSE(last.whole);
  EXPECT_TRUE(last.to_end);
  EXPECT_DOUBLE_EQ(last.from, -0.3);
  const ClipStretch both = parse_clip_stretch("walk.txt@0.25:0.6");
  EXPECT_DOUBLE_EQ(both.from, 0.25);
  EXPECT_DOUBLE_EQ(both.to, 0.6);
  EXPECT_FALSE(both.to_end);
  for (const char* bad : {"walk.txt@", "walk.txt@x", "walk.txt@0.2:", "walk.txt@0.2:0.5:0.7", "@0.3", "walk.txt@ 0.3", "walk.txt@nan"})
    EXPECT_NE(test::error_of([&] { (void)parse_clip_stretch(bad); }).find(std::string("'") + bad + "': expected FILE, FILE@FROM or FILE@FROM:TO"),
              std::string::npos)
        << bad;

  const Clip c = one_second_clip();
  EXPECT_EQ(cut(c, whole).num_frames(), 11);
  EXPECT_EQ(cut(c, whole).loop, LoopMode::Wrap);  // a whole clip is the clip itself
  // The last 0.3 s: 0.7 to 1.0 s, frames 7 to 10.
  const Clip end = cut(c, parse_clip_stretch("ten.mclip@-0.3"));
  ASSERT_EQ(end.num_frames(), 4);
  EXPECT_DOUBLE_EQ(end.frames.front().root_pos.x(), 0.1 * 7);
  EXPECT_DOUBLE_EQ(end.frames.back().root_pos.x(), 0.1 * 10);
  EXPECT_EQ(end.loop, LoopMode::None);
  // 0.25 to 0.6 s as excerpt gives it; 0.2 s to 0.1 s before the end: frames 2 to 9.
  EXPECT_DOUBLE_EQ(cut(c, both).frames.front().root_pos.x(), 0.1 * 3);
  const Clip middle = cut(c, parse_clip_stretch("ten.mclip@0.2:-0.1"));
  ASSERT_EQ(middle.num_frames(), 8);
  EXPECT_DOUBLE_EQ(middle.frames.back().root_pos.x(), 0.1 * 9);
  for (const char* outside : {"ten.mclip@-1.5", "ten.mclip@0.5:1.5", "ten.mclip@0.6:0.2", "ten.mclip@1"})
    EXPECT_NE(test::error_of([&] { (void)cut(c, parse_clip_stretch(outside)); }).find("is not a stretch of clip 'ten', which is 1.000 s long"),
              std::string::npos)
        << outside;
  EXPECT_NE(test::error_of([&] { (void)cut(c, parse_clip_stretch("ten.mclip@0.31:0.39")); }).find("ten.mclip@0.31:0.39: excerpt of clip 'ten'"),
            std::string::npos);
}

TEST(Mirror, PairsByName) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", p);
  const Skeleton sk = load_deepmimic_character(p).skeleton;
  const std::vector<int> twin = mirror_map(sk);
  EXPECT_EQ(twin[static_cast<std::size_t>(sk.find("chest"))], sk.find("chest"));
  EXPECT_EQ(twin[static_cast<std::size_t>(sk.find("right_knee"))], sk.find("left_knee"));
  EXPECT_EQ(twin[static_cast<std::size_t>(sk.find("left_wrist"))], sk.find("right_wrist"));
}

TEST(Mirror, CmuNamesPair) {
  std::filesystem::path path;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", path);
  const Skeleton sk = load_bvh(path, AxisConvention{"y", "z", 0.056444}).skeleton;
  const std::vector<int> twin = mirror_map(sk);
  EXPECT_EQ(twin[static_cast<std::size_t>(sk.find("LHipJoint"))], sk.find("RHipJoint"));
  EXPECT_EQ(twin[static_cast<std::size_t>(sk.find("lhand"))], sk.find("rhand"));
  EXPECT_EQ(twin[static_cast<std::size_t>(sk.find("LeftShoulder"))], sk.find("RightShoulder"));
  EXPECT_EQ(twin[static_cast<std::size_t>(sk.find("lowerback"))], sk.find("lowerback"));
}

TEST(Mirror, ReflectsLinkPositionsOfASymmetricSkeleton) {
  Clip c;
  c.skeleton = tiny_skeleton();
  Pose p = rest_pose(c.skeleton, Vec3(1, 2, 1));
  p.rot[0] = axis_rotation('z', 0.4);
  p.rot[1] = axis_rotation('x', 0.3) * axis_rotation('y', 0.5);
  p.rot[2] = axis_rotation('y', -0.2);
  c.frames = {p};
  const Clip m = mirror(c);
  const LinkFrames a = forward_kinematics(c.skeleton, c.frames[0]);
  const LinkFrames b = forward_kinematics(m.skeleton, m.frames[0]);
  // The mirrored left foot is the original right foot reflected through y = 0, and vice versa.
  const Vec3 flip(1, -1, 1);
  EXPECT_TRUE(b.site_pos[0].isApprox(a.site_pos[1].cwiseProduct(flip), 1e-12));
  EXPECT_TRUE(b.site_pos[1].isApprox(a.site_pos[0].cwiseProduct(flip), 1e-12));
  EXPECT_NEAR(heading_angle(m.frames[0].rot[0]), -0.4, 1e-12);  // turning left becomes right
}

TEST(Mirror, TwiceIsIdentity) {
  std::filesystem::path path;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", path);
  const Clip cmu = load_bvh(path, AxisConvention{"y", "z", 0.056444});
  EXPECT_LT(max_pose_difference(cmu, mirror(mirror(cmu))), 1e-9);
  const Clip walk = load_walk();
  EXPECT_LT(max_pose_difference(walk, mirror(mirror(walk))), 1e-9);
  EXPECT_GT(max_pose_difference(walk, mirror(walk)), 0.1);  // and once is not
}

TEST(Kinematics, VelocitiesOfAConstantSpinAndDrift) {
  Clip c;
  c.skeleton = tiny_skeleton();
  c.fps = 20;
  for (int i = 0; i < 6; ++i) {
    Pose p = rest_pose(c.skeleton, Vec3(0.1 * i, 0, 1));
    p.rot[0] = axis_rotation('z', 0.05 * i);
    p.rot[1] = axis_rotation('x', 0.1 * i);
    c.frames.push_back(p);
  }
  const auto v = clip_velocities(c);
  for (const PoseVelocity& pv : v) {  // one-sided at the ends, central inside: all exact here
    EXPECT_TRUE(pv.root_lin.isApprox(Vec3(2.0, 0, 0), 1e-9));
    EXPECT_TRUE(pv.root_ang.isApprox(Vec3(0, 0, 1.0), 1e-9));
    EXPECT_TRUE(pv.joint_ang[1].isApprox(Vec3(2.0, 0, 0), 1e-9));
  }
}

// The left leg turns 0.1, 0.4, then 0.2 rad about x between frames at 20 fps (2, 8, 4 rad/s),
// the right one 0.05 rad about y once (1 rad/s); the root's own spin is not a joint's.
TEST(Kinematics, PeakJointSpeedsAreTheFastestTurnBetweenFrames) {
  Clip c;
  c.skeleton = tiny_skeleton();
  c.fps = 20;
  const double left[] = {0.0, 0.1, 0.5, 0.7}, right[] = {0.0, 0.0, 0.05, 0.05};
  for (int i = 0; i < 4; ++i) {
    Pose p = rest_pose(c.skeleton, Vec3(0, 0, 1));
    p.rot[0] = axis_rotation('z', 1.0 * i);
    p.rot[1] = axis_rotation('x', left[i]);
    p.rot[2] = axis_rotation('y', right[i]);
    c.frames.push_back(p);
  }
  const std::vector<double> peak = peak_joint_speeds(c);
  ASSERT_EQ(peak.size(), 3u);
  EXPECT_EQ(peak[0], 0.0);
  EXPECT_NEAR(peak[1], 8.0, 1e-9);
  EXPECT_NEAR(peak[2], 1.0, 1e-9);
}

TEST(Kinematics, WrapClipContinuesWithDrift) {
  std::filesystem::path p;
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", p);
  const Clip walk = load_walk();
  const Vec3 drift = walk.frames.back().root_pos - walk.frames.front().root_pos;
  // One cycle later the pose is the same, displaced by the cycle's drift on the ground.
  const Pose a = walk.sample(0.2), b = walk.sample(0.2 + walk.duration());
  EXPECT_NEAR((b.root_pos - a.root_pos).x(), drift.x(), 1e-9);
  EXPECT_NEAR((b.root_pos - a.root_pos).y(), drift.y(), 1e-9);
  EXPECT_NEAR(b.root_pos.z(), a.root_pos.z(), 1e-9);
  // The walk's last frame faces 6.9 degrees off its first; the loop still does not turn.
  for (std::size_t j = 0; j < a.rot.size(); ++j) EXPECT_LT(rotation_distance(a.rot[j], b.rot[j]), 1e-9);
}

TEST(Clip, WrapCyclesTranslateWithoutTurning) {
  // Three frames 1 s apart along +x; the last faces 10 degrees left of the first (as DeepMimic's
  // run and walk clips do, whose root paths are straight).
  Clip c;
  c.skeleton = tiny_skeleton();
  c.fps = 1.0;
  c.loop = LoopMode::Wrap;
  for (int f = 0; f < 3; ++f) {
    Pose p = rest_pose(c.skeleton, Vec3(f, 0, 1));
    if (f == 2) p.rot[0] = axis_rotation('z', deg_to_rad(10.0));
    c.frames.push_back(p);
  }
  // One cycle moves the root by the first-to-last translation (2, 0, 0) and nothing else.
  for (double t : {0.0, 0.5, 1.0, 1.25}) {
    const Pose a = c.sample(t), b = c.sample(t + 2.0), back = c.sample(t - 2.0);
    EXPECT_TRUE((b.root_pos - a.root_pos).isApprox(Vec3(2, 0, 0), 1e-12)) << "t " << t;
    EXPECT_TRUE((a.root_pos - back.root_pos).isApprox(Vec3(2, 0, 0), 1e-12)) << "t " << t;
    EXPECT_LT(rotation_distance(a.rot[0], b.rot[0]), 1e-12) << "t " << t;
  }
  // Across the seam the root stays on the line y = 0: frame 3 is frame 1 moved to x = 3.
  EXPECT_TRUE(c.sample(3.0).root_pos.isApprox(Vec3(3, 0, 1), 1e-12));
  EXPECT_LT(rotation_distance(c.sample(3.0).rot[0], Quat::Identity()), 1e-12);
  EXPECT_NEAR(c.sample(2.5).root_pos.y(), 0.0, 1e-12);
}

TEST(Kinematics, HeadingFrameExpressesPointsRelativeToFacing) {
  Pose p;
  p.root_pos = Vec3(1, 1, 0.9);
  p.rot = {axis_rotation('z', kPi / 2) * axis_rotation('y', 0.3)};  // facing +Y, pitched
  const HeadingFrame h = HeadingFrame::of(p);
  EXPECT_TRUE(h.origin.isApprox(Vec3(1, 1, 0)));
  // A point 1 m along world +Y from the root is 1 m straight ahead.
  EXPECT_TRUE(h.to_local(Vec3(1, 2, 0.9)).isApprox(Vec3(1, 0, 0.9), 1e-12));
}

TEST(Lying, SideFollowsTheForwardAxisAndAClipBeginsLyingBelowHalfItsHighestRoot) {
  const Skeleton sk = tiny_skeleton();
  Pose p = rest_pose(sk, Vec3(0, 0, 0.9));
  EXPECT_EQ(lying_side(p), 0);  // standing: forward is horizontal
  // Pitched about Y by -60 degrees the forward axis points 60 degrees up (sin 0.87 > 0.5): face up.
  p.rot[0] = Quat(Eigen::AngleAxisd(-kPi / 3, Vec3::UnitY()));
  EXPECT_EQ(lying_side(p), 1);
  p.rot[0] = Quat(Eigen::AngleAxisd(kPi / 3, Vec3::UnitY()));
  EXPECT_EQ(lying_side(p), -1);
  // 20 degrees (sin 0.34) is a lean, not lying; on its side (rolled about X) neither.
  p.rot[0] = Quat(Eigen::AngleAxisd(kPi / 9, Vec3::UnitY()));
  EXPECT_EQ(lying_side(p), 0);
  p.rot[0] = Quat(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX()));
  EXPECT_EQ(lying_side(p), 0);

  Clip clip;
  clip.skeleton = sk;
  for (const double z : {0.1, 0.5, 0.9}) clip.frames.push_back(rest_pose(sk, Vec3(0, 0, z)));
  EXPECT_TRUE(begins_lying(clip));  // 0.1 < 0.45
  clip.frames.front().root_pos.z() = 0.46;
  EXPECT_FALSE(begins_lying(clip));  // a crouch at half the height: not lying
  std::reverse(clip.frames.begin(), clip.frames.end());
  clip.frames.back().root_pos.z() = 0.1;
  EXPECT_FALSE(begins_lying(clip));  // a fall: it ends lying
  EXPECT_FALSE(begins_lying(Clip{}));
}
