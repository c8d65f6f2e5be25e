// Importers on the shared data: frame counts, durations, known values, plausible FK heights.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "motion/bvh.hpp"
#include "motion/clip_io.hpp"
#include "motion/deepmimic.hpp"
#include "motion/kinematics.hpp"
#include "test_data.hpp"

using namespace mimic;

namespace {
AxisConvention cmu_axes() { return AxisConvention{"y", "z", 0.056444}; }

// Top of the humanoid's head: the neck body's sphere centre plus its radius, in the world.
double head_top(const DeepMimicCharacter& ch, const LinkFrames& fk) {
  const int neck = ch.skeleton.find("neck");
  const BodyDef& b = ch.bodies[static_cast<std::size_t>(neck)];
  const Vec3 centre = fk.joint_pos[static_cast<std::size_t>(neck)] + fk.joint_rot[static_cast<std::size_t>(neck)] * b.pos;
  return centre.z() + 0.5 * b.size.z();
}
}  // namespace

TEST(DeepMimicImport, HumanoidCharacterMatchesFile) {
  std::filesystem::path path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", path);
  const DeepMimicCharacter ch = load_deepmimic_character(path);
  EXPECT_EQ(ch.skeleton.num_joints(), 15);
  EXPECT_EQ(ch.skeleton.dof_count(), 34);  // 6 + 8 spherical * 3 + 4 revolute
  EXPECT_EQ(ch.bodies.size(), 15u);
  double mass = 0;
  for (const BodyDef& b : ch.bodies) mass += b.mass;
  EXPECT_NEAR(mass, 45.0, 1e-9);
  // right_hip is attached at DeepMimic (0, 0, 0.084887): mimic's y is DeepMimic's -z.
  const Joint& hip = ch.skeleton.joints[static_cast<std::size_t>(ch.skeleton.find("right_hip"))];
  EXPECT_TRUE(hip.offset.isApprox(Vec3(0, -0.084887, 0), 1e-12));
  const Joint& knee = ch.skeleton.joints[static_cast<std::size_t>(ch.skeleton.find("right_knee"))];
  EXPECT_EQ(knee.type, JointType::Revolute);
  EXPECT_TRUE(knee.axis.isApprox(Vec3(0, -1, 0)));
  EXPECT_DOUBLE_EQ(knee.torque_limit, 150);
  EXPECT_EQ(ch.skeleton.joints[8].type, JointType::Fixed);  // right_wrist
  // Foot box: DeepMimic size (0.177, 0.055, 0.09) is (x, y-up, z); mimic (x, y-left, z-up).
  EXPECT_TRUE(ch.bodies[5].size.isApprox(Vec3(0.177, 0.09, 0.055)));
}

TEST(DeepMimicImport, WalkFramesDurationAndKnownValue) {
  std::filesystem::path ch_path, path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch_path);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", path);
  const DeepMimicCharacter ch = load_deepmimic_character(ch_path);
  const Clip clip = load_deepmimic_motion(path, ch.skeleton);
  EXPECT_EQ(clip.num_frames(), 39);
  EXPECT_EQ(clip.loop, LoopMode::Wrap);
  EXPECT_NEAR(clip.fps, 1.0 / 0.033332, 1e-9);
  EXPECT_NEAR(clip.duration(), 38 * 0.033332, 1e-9);
  // Frame 0 root: DeepMimic (0, 0.847532, 0) -> mimic z = 0.847532.
  EXPECT_NEAR(clip.frames[0].root_pos.z(), 0.847532, 1e-12);
  // right_knee angle at frame 0 is the file's 20th value after dt/root: read it back.
  const int knee = ch.skeleton.find("right_knee");
  const double angle = revolute_angle(ch.skeleton.joints[static_cast<std::size_t>(knee)], clip.frames[0].rot[static_cast<std::size_t>(knee)]);
  EXPECT_NEAR(angle, -0.2491160000, 1e-9);
}

TEST(DeepMimicImport, WalkFkHeightsArePlausible) {
  std::filesystem::path ch_path, path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch_path);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", path);
  const DeepMimicCharacter ch = load_deepmimic_character(ch_path);
  const Clip clip = load_deepmimic_motion(path, ch.skeleton);
  const auto rank = static_cast<std::size_t>(ch.skeleton.find("right_ankle"));
  const auto lank = static_cast<std::size_t>(ch.skeleton.find("left_ankle"));
  double lowest_ankle = 1e9;
  for (const Pose& p : clip.frames) {
    const LinkFrames fk = forward_kinematics(ch.skeleton, p);
    const double top = head_top(ch, fk);
    EXPECT_GT(top, 1.5);
    EXPECT_LT(top, 1.7);
    lowest_ankle = std::min({lowest_ankle, fk.joint_pos[rank].z(), fk.joint_pos[lank].z()});
    EXPECT_GT(fk.joint_pos[rank].z(), 0.0);
  }
  // Ankle joints sit ~5 cm above the sole (foot box 0.0225 + 0.0275 below the joint).
  EXPECT_NEAR(lowest_ankle, 0.05, 0.03);
}

TEST(DeepMimicImport, DogCharacterAndTrot) {
  std::filesystem::path ch_path, path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/dog3d.txt", ch_path);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/dog3d_trot.txt", path);
  const DeepMimicCharacter ch = load_deepmimic_character(ch_path);
  EXPECT_EQ(ch.skeleton.num_joints(), 23);
  const Clip clip = load_deepmimic_motion(path, ch.skeleton);
  EXPECT_EQ(clip.num_frames(), 32);
  EXPECT_NEAR(clip.fps, 1.0 / 0.0166666992, 1e-6);
  // Paws stay near the ground and below the root throughout the trot.
  for (const Pose& p : clip.frames) {
    const LinkFrames fk = forward_kinematics(ch.skeleton, p);
    for (const char* paw : {"left_toe", "right_toe"}) {
      const double z = fk.joint_pos[static_cast<std::size_t>(ch.skeleton.find(paw))].z();
      EXPECT_GT(z, -0.01);
      EXPECT_LT(z, fk.joint_pos[0].z());
    }
  }
}

TEST(DeepMimicImport, EveryHumanoidMotionLoads) {
  std::filesystem::path ch_path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch_path);
  for (const auto& entry : std::filesystem::directory_iterator(ch_path.parent_path().parent_path() / "motions")) {
    if (entry.path().filename().string().rfind("humanoid3d_", 0) != 0) continue;
    const Clip clip = load_motion(entry.path());  // character found by naming convention
    EXPECT_GT(clip.num_frames(), 10) << entry.path();
    clip.validate();
  }
}

TEST(DeepMimicImport, MotionExportRoundTrips) {
  std::filesystem::path ch_path, path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch_path);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_run.txt", path);
  const Skeleton sk = load_deepmimic_character(ch_path).skeleton;
  const Clip a = load_deepmimic_motion(path, sk);
  const Clip b = parse_deepmimic_motion(write_deepmimic_motion(a), "export.txt", sk);
  ASSERT_EQ(a.num_frames(), b.num_frames());
  for (int f = 0; f < a.num_frames(); ++f) {
    const auto fu = static_cast<std::size_t>(f);
    EXPECT_LT((a.frames[fu].root_pos - b.frames[fu].root_pos).norm(), 1e-8);
    for (std::size_t j = 0; j < a.frames[fu].rot.size(); ++j)
      EXPECT_LT(rotation_distance(a.frames[fu].rot[j], b.frames[fu].rot[j]), 1e-7);
  }
}

TEST(BvhImport, CmuWalkFramesDurationAndChannels) {
  std::filesystem::path path;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", path);
  const Clip clip = load_bvh(path, cmu_axes());
  EXPECT_EQ(clip.num_frames(), 994);
  EXPECT_NEAR(clip.fps, 1.0 / 0.0083333, 1e-6);
  EXPECT_NEAR(clip.duration(), 993 * 0.0083333, 1e-9);
  EXPECT_EQ(clip.skeleton.num_joints(), 31);
  EXPECT_EQ(clip.skeleton.sites.size(), 7u);  // end sites: 2 toes, head, 2 fingers, 2 thumbs
  // Frame 0 root: BVH (5.23, 16.9002, -33.8986) units; mimic x = bvh z, y = bvh x, z = bvh y.
  EXPECT_TRUE(clip.frames[0].root_pos.isApprox(0.056444 * Vec3(-33.8986, 5.2300, 16.9002), 1e-9));
  // LeftKnee (Z Y X order) at frame 0: BVH angles (6.3664, 14.7742, 46.4350) degrees.
  const int knee = clip.skeleton.find("LeftKnee");
  const double zyx[3] = {deg_to_rad(6.3664), deg_to_rad(14.7742), deg_to_rad(46.4350)};
  const Quat src = euler_intrinsic("ZYX", zyx);
  const Quat basis = source_to_mimic(cmu_axes());
  const Quat expect = basis * src * basis.conjugate();
  EXPECT_LT(rotation_distance(clip.frames[0].rot[static_cast<std::size_t>(knee)], expect), 1e-9);
}

TEST(BvhImport, CmuFkHeightsArePlausible) {
  std::filesystem::path path;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", path);
  const Clip clip = load_bvh(path, cmu_axes());
  const auto head = static_cast<std::size_t>(clip.skeleton.find_site("Head_end"));
  const auto ltoe = static_cast<std::size_t>(clip.skeleton.find("LeftToe"));
  double lowest = 1e9, head_lo = 1e9, head_hi = -1e9;
  for (const Pose& p : clip.frames) {
    const LinkFrames fk = forward_kinematics(clip.skeleton, p);
    head_lo = std::min(head_lo, fk.site_pos[head].z());
    head_hi = std::max(head_hi, fk.site_pos[head].z());
    lowest = std::min(lowest, fk.joint_pos[ltoe].z());
  }
  // Standing at the start, the head's end site is at ~1.45 m; the stylised walk crouches to
  // ~0.8 m around frame 360 but never lies down or floats.
  EXPECT_NEAR(forward_kinematics(clip.skeleton, clip.frames[0]).site_pos[head].z(), 1.45, 0.05);
  EXPECT_GT(head_lo, 0.6);
  EXPECT_LT(head_hi, 1.6);
  EXPECT_NEAR(lowest, 0.0, 0.05);  // feet reach the floor
}

TEST(NativeClip, RoundTripsImportedClipsWithin1e6) {
  std::filesystem::path bvh_path, ch_path, walk_path;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_03.bvh", bvh_path);
  MIMIC_REQUIRE_SHARED("deepmimic/characters/dog3d.txt", ch_path);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/dog3d_canter.txt", walk_path);
  for (const Clip& a : {load_bvh(bvh_path, cmu_axes()), load_deepmimic_motion(walk_path, load_deepmimic_character(ch_path).skeleton)}) {
    const auto dir = test::temp_dir("native_round_trip");
    save_clip(a, dir / "c.mclip");
    const Clip b = load_motion(dir / "c.mclip");
    ASSERT_EQ(a.num_frames(), b.num_frames());
    EXPECT_EQ(a.loop, b.loop);
    EXPECT_NEAR(a.fps, b.fps, 1e-6);
    ASSERT_EQ(a.skeleton.num_joints(), b.skeleton.num_joints());
    for (int j = 0; j < a.skeleton.num_joints(); ++j) {
      const auto ju = static_cast<std::size_t>(j);
      EXPECT_EQ(a.skeleton.joints[ju].name, b.skeleton.joints[ju].name);
      EXPECT_EQ(a.skeleton.joints[ju].type, b.skeleton.joints[ju].type);
      EXPECT_LT((a.skeleton.joints[ju].offset - b.skeleton.joints[ju].offset).norm(), 1e-6);
    }
    double worst = 0;
    for (int f = 0; f < a.num_frames(); ++f) {
      const auto fu = static_cast<std::size_t>(f);
      worst = std::max(worst, (a.frames[fu].root_pos - b.frames[fu].root_pos).cwiseAbs().maxCoeff());
      for (std::size_t j = 0; j < a.frames[fu].rot.size(); ++j)
        worst = std::max(worst, (a.frames[fu].rot[j].coeffs() - b.frames[fu].rot[j].coeffs()).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-6) << a.name;
  }
}

// CMU's own ASF/AMC files are not in ../shared; a user who has them points $MIMIC_CMU_ASF_AMC
// at a directory of them (e.g. subjects/07/ with 07.asf, 07_01.amc, ...).
TEST(AsfAmcImport, UserCmuFilesLoadWhenPresent) {
  const char* dir = std::getenv("MIMIC_CMU_ASF_AMC");
  if (!dir || !std::filesystem::is_directory(dir)) GTEST_SKIP() << "set MIMIC_CMU_ASF_AMC to a directory of CMU .asf/.amc files to run this";
  int clips = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".amc") continue;
    const Clip clip = load_motion(entry.path());
    clip.validate();
    EXPECT_GT(clip.num_frames(), 0) << entry.path();
    // Standing subjects: the head is well above the feet in the first frame.
    const LinkFrames fk = forward_kinematics(clip.skeleton, clip.frames[0]);
    double lo = 1e9, hi = -1e9;
    for (const Vec3& p : fk.joint_pos) lo = std::min(lo, p.z()), hi = std::max(hi, p.z());
    EXPECT_GT(hi - lo, 1.0) << entry.path();
    ++clips;
  }
  EXPECT_GT(clips, 0) << "no .amc files in " << dir;
}

TEST(NativeClip, NamesWithControlCharactersRoundTrip) {
  Clip c;
  c.name = "a\n---\nb\t\"q\"\\";
  c.skeleton.joints.push_back(Joint{"root", -1, JointType::Free, Vec3::Zero(), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  c.frames.push_back(rest_pose(c.skeleton, Vec3(0, 0, 1)));
  const Clip back = parse_clip(write_clip(c), "names.mclip");
  EXPECT_EQ(back.name, c.name);
  EXPECT_EQ(back.num_frames(), 1);
}

TEST(NativeClip, HugeFrameCountsAreRefusedBeforeAllocating) {
  Clip c;
  c.skeleton.joints.push_back(Joint{"root", -1, JointType::Free, Vec3::Zero(), Quat::Identity(), Vec3::UnitZ(), {}, 0, false});
  c.frames.push_back(rest_pose(c.skeleton));
  std::string text = write_clip(c);
  text.replace(text.find("frames: 1"), 9, "frames: 9999999");
  // 9,999,999 frames of one joint would be allowed; of 4,096 joints they exceed the bound.
  for (int j = 1; j < 4096; ++j) {
    const std::string line = "  - {name: \"j" + std::to_string(j) + "\", parent: 0, type: fixed}\n";
    text.insert(text.find("sites:"), line);
  }
  try {
    parse_clip(text, "huge.mclip");
    FAIL() << "accepted";
  } catch (const ParseError& e) {
    EXPECT_NE(std::string(e.what()).find("clip too large"), std::string::npos) << e.what();
  }
}
