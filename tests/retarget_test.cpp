// Retargeting CMU capture onto the DeepMimic humanoid, and the map file's errors.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.hpp"
#include "motion/bvh.hpp"
#include "motion/deepmimic.hpp"
#include "motion/kinematics.hpp"
#include "motion/retarget.hpp"
#include "test_data.hpp"

using namespace mimic;

namespace {
const std::filesystem::path kMap = std::filesystem::path(MIMIC_SOURCE_DIR) / "data/retarget/cmu_to_humanoid3d.yaml";
}

TEST(Retarget, CmuWalkOnHumanoidKeepsFeetOnTheFloor) {
  std::filesystem::path bvh, ch;
  MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", bvh);
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch);
  const Clip src = load_bvh(bvh, AxisConvention{"y", "z", 0.056444});
  const Skeleton target = load_deepmimic_character(ch).skeleton;
  RetargetReport report;
  const Clip out = retarget(src, target, load_retarget_map(kMap), &report);
  ASSERT_EQ(out.num_frames(), src.num_frames());
  EXPECT_EQ(out.skeleton.num_joints(), 15);
  EXPECT_EQ(out.skeleton.sites.size(), 4u);  // the map's sole corners
  EXPECT_NEAR(report.scale, 1.05, 0.05);     // subject 131 is a little shorter than humanoid3d
  // Per frame, the lowest sole corner: never below the floor, and within 6 cm of it always
  // (someone is always standing on a foot during this walk).
  std::vector<double> lowest;
  for (const Pose& p : out.frames) {
    const LinkFrames fk = forward_kinematics(out.skeleton, p);
    lowest.push_back(std::min({fk.site_pos[0].z(), fk.site_pos[1].z(), fk.site_pos[2].z(), fk.site_pos[3].z()}));
  }
  std::sort(lowest.begin(), lowest.end());
  EXPECT_NEAR(lowest.front(), 0.0, 1e-9);
  EXPECT_LT(lowest.back(), 0.08);
  EXPECT_LT(lowest[lowest.size() / 2], 0.04);
  EXPECT_EQ(report.frames_below_floor, 0);
  // End-effector error against the scaled source, per effector. Rotations alone leave the ankles
  // 0.11 m and the wrists 0.13-0.15 m from it in the world (the proportions differ); the map's
  // inverse kinematics brings them within 0.03 m (the root lowered: root-relative errors stay).
  ASSERT_EQ(report.effectors.size(), 5u);
  for (const EffectorError& e : report.effectors) {
    EXPECT_GT(e.mean, 0.0) << e.name;
    EXPECT_LT(e.mean, 0.16) << e.name;
    EXPECT_LE(e.mean, e.max) << e.name;
    if (e.name == "neck") continue;  // not an ik joint
    EXPECT_GT(e.world_mean_before_ik, 0.1) << e.name;
    EXPECT_LT(e.world_mean, 0.03) << e.name;
  }
  // The feet stay put while the source's are in stance: sliding from 0.11-0.14 m/s to almost none.
  ASSERT_EQ(report.contacts.size(), 2u);
  for (const ContactReport& c : report.contacts) {
    EXPECT_GT(c.stance_frames, 200) << c.name;
    EXPECT_GT(c.sliding_before_ik, 0.05) << c.name;
    EXPECT_LT(c.sliding, 0.01) << c.name;
  }
}

TEST(Retarget, OntoItsOwnSkeletonIsTheIdentity) {
  std::filesystem::path ch, walk_path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", walk_path);
  const Skeleton sk = load_deepmimic_character(ch).skeleton;
  const Clip walk = load_deepmimic_motion(walk_path, sk);
  RetargetMap map;
  for (const Joint& j : sk.joints) map.joints.emplace_back(j.name, std::vector<std::string>{j.name});
  map.scale = 1.0;
  map.ground_fix = false;
  map.end_effectors = {"right_wrist", "left_ankle"};
  map.ik = {"right_wrist", "left_ankle"};  // already where the source has them: nothing moves
  RetargetReport report;
  const Clip out = retarget(walk, sk, map, &report);
  for (std::size_t f = 0; f < walk.frames.size(); ++f) {
    EXPECT_LT((out.frames[f].root_pos - walk.frames[f].root_pos).norm(), 1e-12);
    for (std::size_t j = 0; j < sk.joints.size(); ++j)
      EXPECT_LT(rotation_distance(out.frames[f].rot[j], walk.frames[f].rot[j]), 1e-6) << sk.joints[j].name;
  }
  for (const EffectorError& e : report.effectors) EXPECT_LT(e.max, 1e-6);
}

TEST(Retarget, MapErrorsNameTheFileAndTheProblem) {
  EXPECT_THROW(parse_retarget_map("joints: [a, b]", "m.yaml"), ParseError);
  try {
    parse_retarget_map("joints:\n  root: Hips\nscael: 2\n", "m.yaml");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_STREQ(e.what(), "m.yaml:3: unknown key 'scael' (joints, scale, sites, end_effectors, ik, contacts, ground_fix)");
  }
  try {
    parse_retarget_map("joints:\n  root: Hips\nik: [left_ankle]\ncontacts: [left_ankle, right_ankle]\n", "m.yaml");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_STREQ(e.what(), "m.yaml:4: contact 'right_ankle' is not one of the 'ik' joints (a contact is held by inverse kinematics)");
  }
  try {
    parse_retarget_map("joints:\n  root: Hips\nscale: -1\n", "m.yaml");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), 3);
  }
  // Found by the fuzzer (fuzz_retarget_map): a map without 'joints', a site without a name and a
  // key that is a list each crashed on yaml-cpp's invalid node instead of saying what is missing.
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {"scale: 0.5\n", "m.yaml:1: 'joints' must map target joint names to source joint names"},
           {"joints: {root: Hips}\nsites:\n  - {joint: root, offset: [0, 0, 1]}\n", "m.yaml:3: a site needs name, joint and offset: [x, y, z]"},
           {"[joints]: 1\n", "m.yaml:1: a key that is a list, where keys are names"}}) {
    try {
      parse_retarget_map(text, "m.yaml");
      FAIL() << text;
    } catch (const ParseError& e) {
      EXPECT_STREQ(e.what(), message.c_str());
    }
  }
  std::filesystem::path ch, walk_path;
  MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch);
  MIMIC_REQUIRE_SHARED("deepmimic/motions/humanoid3d_walk.txt", walk_path);
  const Skeleton sk = load_deepmimic_character(ch).skeleton;
  const Clip walk = load_deepmimic_motion(walk_path, sk);
  const RetargetMap bad = parse_retarget_map("joints:\n  root: root\n  chest: Spine\n", "m.yaml");
  try {
    retarget(walk, sk, bad);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "m.yaml: source joint 'Spine' does not exist in the source skeleton");
  }
}
