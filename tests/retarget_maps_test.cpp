// The built-in retarget maps, how a map finds its source joints (alternatives, a name prefix),
// which map fits a clip, and a source that faces another way at rest.
#include <gtest/gtest.h>

#include <map>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/math.hpp"
#include "motion/bvh.hpp"
#include "motion/deepmimic.hpp"
#include "motion/retarget_maps.hpp"
#include "test_data.hpp"

using namespace mimic;

namespace {

// The shared CMU walk's joints (131_01.bvh) given another convention's names: "L" for the left
// side's (Left -> L), the right's made from them.
Clip renamed(Clip clip, const std::string& prefix, const std::map<std::string, std::string>& left_and_middle) {
  std::map<std::string, std::string> names;
  for (const auto& [from, to] : left_and_middle) {
    names[from] = to;
    if (from.rfind("Left", 0) == 0) {
      std::string right = to;
      for (const auto& [l, r] : {std::pair{"Left", "Right"}, std::pair{"L_", "R_"}, std::pair{"left_", "right_"}})
        if (const std::size_t at = right.find(l); at != std::string::npos) {
          right.replace(at, std::string(l).size(), r);
          break;
        }
      if (right == to && !to.empty() && to[0] == 'l') right[0] = 'r';  // Acclaim: lfemur -> rfemur
      names["Right" + from.substr(4)] = right;
    }
  }
  for (Joint& j : clip.skeleton.joints)
    if (const auto it = names.find(j.name); it != names.end()) j.name = prefix + it->second;
  return clip;
}

// Mixamo's names with its prefix; SMPL's two spellings; CMU's Acclaim bone names.
Clip renamed_as_mixamo(const Clip& clip, const std::string& chest = "Spine2") {
  return renamed(clip, "mixamorig:",
                 {{"Hips", "Hips"}, {"LeftHip", "LeftUpLeg"}, {"LeftKnee", "LeftLeg"}, {"LeftAnkle", "LeftFoot"}, {"LeftShoulder", "LeftArm"},
                  {"LeftElbow", "LeftForeArm"}, {"LeftWrist", "LeftHand"}, {"Chest2", chest}, {"Head", "Head"}});
}
Clip renamed_as_smpl(const Clip& clip, bool lower_case) {
  const auto n = [&](const char* upper, const char* lower) { return std::string(lower_case ? lower : upper); };
  return renamed(clip, "",
                 {{"Hips", n("Pelvis", "pelvis")}, {"LeftHip", n("L_Hip", "left_hip")}, {"LeftKnee", n("L_Knee", "left_knee")},
                  {"LeftAnkle", n("L_Ankle", "left_ankle")}, {"LeftShoulder", n("L_Shoulder", "left_shoulder")},
                  {"LeftElbow", n("L_Elbow", "left_elbow")}, {"LeftWrist", n("L_Wrist", "left_wrist")}, {"Chest2", n("Spine3", "spine3")},
                  {"Head", n("Head", "head")}});
}
Clip renamed_as_acclaim(const Clip& clip) {
  return renamed(clip, "",
                 {{"Hips", "root"}, {"LeftHip", "lfemur"}, {"LeftKnee", "ltibia"}, {"LeftAnkle", "lfoot"}, {"LeftShoulder", "lhumerus"},
                  {"LeftElbow", "lradius"}, {"LeftWrist", "lwrist"}, {"Chest2", "thorax"}, {"Head", "head"}});
}

Skeleton skeleton_of(const std::vector<std::string>& names) {
  Skeleton sk;
  for (std::size_t i = 0; i < names.size(); ++i) {
    Joint j;
    j.name = names[i];
    j.parent = i == 0 ? -1 : 0;
    j.type = i == 0 ? JointType::Free : JointType::Spherical;
    sk.joints.push_back(j);
  }
  return sk;
}

// The shared CMU walk's first second (120 of its 994 frames, written as a BVH of their own: what
// these tests compare needs no more, and each retarget's inverse kinematics takes seconds per
// hundred frames under the sanitizers) and DeepMimic's humanoid. The tests skip without ../shared.
class RetargetCmu : public testing::Test {
 protected:
  static constexpr int kFrames = 120;
  void SetUp() override {
    std::filesystem::path whole, ch;
    MIMIC_REQUIRE_SHARED("cmu-bvh/131_01.bvh", whole);
    MIMIC_REQUIRE_SHARED("deepmimic/characters/humanoid3d.txt", ch);
    humanoid = load_deepmimic_character(ch).skeleton;
    const std::string text = read_text_file(whole);
    const std::size_t motion = text.find("MOTION"), frame_time = text.find("Frame Time:");
    ASSERT_NE(frame_time, std::string::npos);
    std::size_t end = text.find('\n', frame_time);
    for (int f = 0; f < kFrames && end != std::string::npos; ++f) end = text.find('\n', end + 1);
    bvh = test::temp_dir("retarget_cmu") / "131_01.bvh";
    write_file_atomic(bvh, text.substr(0, motion) + "MOTION\nFrames: " + std::to_string(kFrames) + "\n" + text.substr(frame_time, end + 1 - frame_time));
  }
  Clip cmu(const AxisConvention& axes = AxisConvention{"y", "z", 0.056444}) const { return load_bvh(bvh, axes); }
  std::filesystem::path bvh;
  Skeleton humanoid;
};

}  // namespace

TEST(RetargetMaps, TheBuiltInMapsAreDataRetargetsFilesByName) {
  EXPECT_EQ(builtin_retarget_map_names(),
            (std::vector<std::string>{"cmu_asf_to_humanoid3d", "cmu_to_humanoid3d", "humanoid3d_to_scaled", "mixamo_to_humanoid3d", "smpl_to_humanoid3d"}));
  const RetargetMap mixamo = builtin_retarget_map("mixamo_to_humanoid3d");
  EXPECT_EQ(mixamo.source, "built-in map mixamo_to_humanoid3d");
  ASSERT_EQ(mixamo.joints.size(), 15u);
  EXPECT_EQ(mixamo.joints[1].first, "chest");
  EXPECT_EQ(mixamo.joints[1].second, (std::vector<std::string>{"Spine2", "Spine1"}));
  EXPECT_EQ(mixamo.ik.size(), 4u);
  // The same map by its file and by its name.
  const RetargetMap file = load_retarget_map_or_builtin(std::string(MIMIC_SOURCE_DIR) + "/data/retarget/cmu_to_humanoid3d.yaml");
  const RetargetMap named = load_retarget_map_or_builtin("cmu_to_humanoid3d");
  EXPECT_EQ(file.joints, named.joints);
  EXPECT_EQ(file.contacts, named.contacts);
  try {
    load_retarget_map_or_builtin("mixamo");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "mixamo: no such map file, nor a built-in map (built in: cmu_asf_to_humanoid3d, cmu_to_humanoid3d, humanoid3d_to_scaled, mixamo_to_humanoid3d, smpl_to_humanoid3d)");
  }
}

TEST(RetargetMaps, ASourceJointIsTheFirstOfItsNamesAnsweringByNameOrAfterAPrefix) {
  const Skeleton sk = skeleton_of({"mixamorig:Hips", "Spine1", "a:Hand", "b:Hand", "Spine:Chest"});
  EXPECT_EQ(find_source_joint(sk, {"Hips"}), 0);            // after the prefix
  EXPECT_EQ(find_source_joint(sk, {"mixamorig:Hips"}), 0);  // the whole name
  EXPECT_EQ(find_source_joint(sk, {"Spine2", "Spine1"}), 1);  // the first the skeleton has
  EXPECT_EQ(find_source_joint(sk, {"Hand"}), -1);           // two joints answer: neither
  EXPECT_EQ(find_source_joint(sk, {"Spine"}), -1);          // a prefix is not a name
  EXPECT_EQ(find_source_joint(sk, {"Chest"}), 4);
  // In a map: a list of names; anything else in it is an error at its line.
  EXPECT_EQ(parse_retarget_map("joints:\n  root: [Pelvis, Hips]\n", "m.yaml").joints[0].second, (std::vector<std::string>{"Pelvis", "Hips"}));
  try {
    parse_retarget_map("joints:\n  root: Hips\n  chest: [Spine2, {a: b}]\n", "m.yaml");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_STREQ(e.what(), "m.yaml:3: joints: the source of 'chest' must be a joint name or a list of them (the first the clip has)");
  }
}

TEST_F(RetargetCmu, ClipsNamedAsMixamoSmplOrAcclaimAreFoundByTheirMapsAndRetargetAsTheCmuMapRetargetsTheCmuClip) {
  const Clip capture = cmu();
  ASSERT_EQ(capture.num_frames(), kFrames);
  const Clip mixamo = renamed_as_mixamo(capture), spine1 = renamed_as_mixamo(capture, "Spine1");
  EXPECT_EQ(builtin_maps_fitting(capture.skeleton, humanoid), std::vector<std::string>{"cmu_to_humanoid3d"});
  EXPECT_EQ(builtin_maps_fitting(mixamo.skeleton, humanoid), std::vector<std::string>{"mixamo_to_humanoid3d"});
  EXPECT_EQ(builtin_maps_fitting(spine1.skeleton, humanoid), std::vector<std::string>{"mixamo_to_humanoid3d"});
  EXPECT_TRUE(builtin_maps_fitting(skeleton_of({"Pelvis", "Spine"}), humanoid).empty());
  std::vector<std::string> both;  // CMU's names and Mixamo's in one skeleton: both maps fit (the commands then ask for --map)
  for (const Clip* c : {&capture, &mixamo})
    for (const Joint& j : c->skeleton.joints) both.push_back(j.name);
  EXPECT_EQ(builtin_maps_fitting(skeleton_of(both), humanoid), (std::vector<std::string>{"cmu_to_humanoid3d", "mixamo_to_humanoid3d"}));
  const Clip smpl = renamed_as_smpl(capture, false), smpl_lower = renamed_as_smpl(capture, true), acclaim = renamed_as_acclaim(capture);
  EXPECT_EQ(builtin_maps_fitting(smpl.skeleton, humanoid), std::vector<std::string>{"smpl_to_humanoid3d"});
  EXPECT_EQ(builtin_maps_fitting(smpl_lower.skeleton, humanoid), std::vector<std::string>{"smpl_to_humanoid3d"});
  EXPECT_EQ(builtin_maps_fitting(acclaim.skeleton, humanoid), std::vector<std::string>{"cmu_asf_to_humanoid3d"});
  EXPECT_EQ(mixamo.skeleton.joints[static_cast<std::size_t>(capture.skeleton.find("RightKnee"))].name, "mixamorig:RightLeg");
  EXPECT_EQ(acclaim.skeleton.joints[static_cast<std::size_t>(capture.skeleton.find("RightKnee"))].name, "rtibia");
  // The two maps pair the same joints (the chest with CMU's Chest2, Mixamo's Spine2): the same clip.
  RetargetReport by_cmu, by_mixamo;
  const Clip a = retarget(capture, humanoid, builtin_retarget_map("cmu_to_humanoid3d"), &by_cmu);
  const Clip b = retarget(mixamo, humanoid, builtin_retarget_map("mixamo_to_humanoid3d"), &by_mixamo);
  ASSERT_EQ(a.num_frames(), b.num_frames());
  for (std::size_t f = 0; f < a.frames.size(); ++f) {
    EXPECT_EQ(a.frames[f].root_pos, b.frames[f].root_pos);
    for (std::size_t j = 0; j < a.frames[f].rot.size(); ++j) EXPECT_EQ(a.frames[f].rot[j].coeffs(), b.frames[f].rot[j].coeffs());
  }
  EXPECT_EQ(by_mixamo.source_turn, 0);
  // Without Spine2 the chest takes Spine1 (CMU's Chest2 renamed so), and SMPL's names by its
  // map: the same clip again.
  for (const auto& [clip, map] : {std::pair{spine1, "mixamo_to_humanoid3d"}, std::pair{smpl, "smpl_to_humanoid3d"},
                                  std::pair{smpl_lower, "smpl_to_humanoid3d"}, std::pair{acclaim, "cmu_asf_to_humanoid3d"}}) {
    const Clip c = retarget(clip, humanoid, builtin_retarget_map(map));
    for (std::size_t j = 0; j < c.frames[90].rot.size(); ++j) EXPECT_EQ(c.frames[90].rot[j].coeffs(), a.frames[90].rot[j].coeffs()) << map;
    EXPECT_EQ(c.frames[90].root_pos, a.frames[90].root_pos) << map;
  }
}

TEST_F(RetargetCmu, ASourceReadWithTheWrongForwardAxisIsFollowedFacingTheWayItFaces) {
  const RetargetMap map = builtin_retarget_map("cmu_to_humanoid3d");
  RetargetReport right, wrong;
  const Clip a = retarget(cmu(), humanoid, map, &right);
  // Read with forward x, the capture's forward (+z) lands on mimic's -y: a quarter turn clockwise
  // seen from above, its whole motion turned so.
  const Clip b = retarget(cmu(AxisConvention{"y", "x", 0.056444}), humanoid, map, &wrong);
  EXPECT_EQ(right.source_turn, 0);
  EXPECT_EQ(wrong.source_turn, -90);
  const Quat quarter(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitZ()));
  for (std::size_t f = 0; f < a.frames.size(); f += 30) {
    EXPECT_LT((quarter * a.frames[f].root_pos - b.frames[f].root_pos).norm(), 1e-6) << f;
    EXPECT_LT(rotation_distance(quarter * a.frames[f].rot[0], b.frames[f].rot[0]), 1e-6) << f;
    for (std::size_t j = 1; j < a.frames[f].rot.size(); ++j) EXPECT_LT(rotation_distance(a.frames[f].rot[j], b.frames[f].rot[j]), 1e-6) << f << " " << j;
  }
  // Left as it was, the character would have walked sideways: facing +x, going along -y (a
  // cosine near 0). The cosine between its mean facing over the second and its travel is the one
  // the clip read right gives (below 1: the root of this stylised walk sways and turns).
  const auto facing_along_travel = [](const Clip& clip) {
    Vec3 travel = clip.frames.back().root_pos - clip.frames.front().root_pos, facing = Vec3::Zero();
    for (const Pose& p : clip.frames) facing += p.rot[0] * Vec3::UnitX();
    travel.z() = facing.z() = 0;
    return travel.normalized().dot(facing.normalized());
  };
  EXPECT_NEAR(facing_along_travel(b), facing_along_travel(a), 1e-6);
  EXPECT_GT(facing_along_travel(b), 0.7);
}

TEST_F(RetargetCmu, ASourceReadWithTheWrongUpAxisIsAnErrorThatSaysSo) {
  const RetargetMap map = builtin_retarget_map("cmu_to_humanoid3d");
  // Lying (its depth axis taken for up) and upside down: before, a scale of 139 or a body on its head.
  for (const AxisConvention& axes : {AxisConvention{"z", "y", 0.01}, AxisConvention{"x", "z", 0.01}, AxisConvention{"-y", "z", 0.01}}) {
    try {
      retarget(cmu(axes), humanoid, map);
      FAIL() << axes.up;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("built-in map cmu_to_humanoid3d: the source does not stand up at rest along the up axis it was read with"),
                std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("read it with the right --up"), std::string::npos);
    }
  }
}
