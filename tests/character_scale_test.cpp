// Another body from a DeepMimic character (motion/deepmimic_scale.hpp): each scaled number
// against its hand-computed value, the result read back as a character, and bad input refused.
#include "motion/deepmimic_scale.hpp"

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "motion/deepmimic.hpp"

using namespace mimic;

namespace {

// A root, a chest on it and a knee below it (DeepMimic's axes: y up); a body and a draw shape
// for each.
const std::string kCharacter = R"({
"Skeleton": {
"Joints": [
{"ID": 0, "Name": "root", "Type": "none", "Parent": -1, "AttachX": 0, "AttachY": 0, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "TorqueLim": 0},
{"ID": 1, "Name": "chest", "Type": "spherical", "Parent": 0, "AttachX": 0, "AttachY": 0.2, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "TorqueLim": 200},
{"ID": 2, "Name": "right_knee", "Type": "revolute", "Parent": 0, "AttachX": 0, "AttachY": -0.4, "AttachZ": 0.1, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "LimLow0": -3, "LimHigh0": 0, "TorqueLim": 150}
]
},
"BodyDefs": [
{"ID": 0, "Name": "root", "Shape": "sphere", "Mass": 6, "AttachX": 0, "AttachY": 0.05, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "Param0": 0.2, "Param1": 0, "Param2": 0},
{"ID": 1, "Name": "chest", "Shape": "box", "Mass": 10, "AttachX": 0, "AttachY": 0.1, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "Param0": 0.2, "Param1": 0.3, "Param2": 0.1},
{"ID": 2, "Name": "right_knee", "Shape": "capsule", "Mass": 3, "AttachX": 0, "AttachY": -0.2, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "Param0": 0.1, "Param1": 0.3, "Param2": 0}
],
"DrawShapeDefs": [
{"ID": 0, "Name": "knee\tshape", "Shape": "capsule", "ParentJoint": 2, "AttachX": 0, "AttachY": -0.2, "AttachZ": 0, "Param0": 0.1, "Param1": 0.3, "Param2": 0}
]
}
)";

const std::string kController = R"({
"UpdateRate": 30,
"PDControllers": [
{"ID": 0, "Name": "root", "Kp": 0, "Kd": 0},
{"ID": 1, "Name": "chest", "Kp": 1000, "Kd": 100},
{"ID": 2, "Name": "right_knee", "Kp": 500, "Kd": 50}
]
}
)";

std::string error_of(const CharacterScaling& s, const std::string& text = kCharacter) {
  try {
    (void)scale_deepmimic_character(text, "small.txt", s);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(CharacterScale, SegmentsMassesAndGainsTakeTheirFactors) {
  CharacterScaling s;
  s.lengths = {{"*", 1.1}, {"knee", 1.5}};  // every segment 1.1, the shin 1.5
  s.mass = 2;
  const ScaledCharacter out = scale_deepmimic_character(kCharacter, "small.txt", s);
  ASSERT_EQ(out.factors, (std::vector<double>{1.1, 1.1, 1.5}));
  // Gains: mass 2 times the mean length factor (1.1 + 1.1 + 1.5) / 3.
  EXPECT_NEAR(out.gains, 2 * 3.7 / 3, 1e-12);
  const DeepMimicCharacter before = parse_deepmimic_character(kCharacter, "small.txt");
  const DeepMimicCharacter after = parse_deepmimic_character(out.character, "scaled.txt");
  // A joint's offset takes its parent's factor (the root's 1.1), its body its own.
  ASSERT_EQ(after.skeleton.joints.size(), 3u);
  EXPECT_LT((after.skeleton.joints[1].offset - 1.1 * before.skeleton.joints[1].offset).norm(), 1e-9);
  EXPECT_LT((after.skeleton.joints[2].offset - 1.1 * before.skeleton.joints[2].offset).norm(), 1e-9);
  EXPECT_LT((after.bodies[2].pos - 1.5 * before.bodies[2].pos).norm(), 1e-9);
  EXPECT_LT((after.bodies[2].size - 1.5 * before.bodies[2].size).norm(), 1e-9);  // 0.15 across, 0.45 long
  EXPECT_NEAR(after.bodies[2].size.z(), 0.45, 1e-9);
  EXPECT_LT((after.bodies[1].size - 1.1 * before.bodies[1].size).norm(), 1e-9);
  EXPECT_NEAR(after.bodies[0].mass, 12, 1e-9);
  EXPECT_NEAR(after.bodies[1].mass, 20, 1e-9);
  EXPECT_NEAR(after.skeleton.joints[1].torque_limit, 200 * out.gains, 1e-6);
  EXPECT_NEAR(after.skeleton.joints[2].torque_limit, 150 * out.gains, 1e-6);
  // What is not a length, mass or gain stays: names, types, limits, the draw shape's parent.
  EXPECT_EQ(after.skeleton.joints[2].name, "right_knee");
  EXPECT_EQ(after.skeleton.joints[2].limits, before.skeleton.joints[2].limits);
  EXPECT_EQ(after.bodies[1].shape, "box");
  EXPECT_NE(out.character.find("\"ParentJoint\": 2"), std::string::npos);
  EXPECT_NE(out.character.find("\"knee\\u0009shape\""), std::string::npos);  // an escaped name stays escaped
  EXPECT_NE(out.character.find("\"Param1\": 0.45"), std::string::npos);  // the draw shape, the knee's factor

  // The controller: Kp and Kd times the gain factor, the rest kept.
  const std::string ctrl = scale_deepmimic_controller(kController, "small_ctrl.txt", 2.5);
  const std::vector<PdGain> gains = parse_deepmimic_pd_gains(ctrl, "scaled_ctrl.txt", after.skeleton);
  EXPECT_NEAR(gains[1].kp, 2500, 1e-9);
  EXPECT_NEAR(gains[2].kd, 125, 1e-9);
  EXPECT_NE(ctrl.find("\"UpdateRate\": 30"), std::string::npos);
  // An explicit gain factor wins over the default.
  s.gains = 3;
  EXPECT_DOUBLE_EQ(scale_deepmimic_character(kCharacter, "small.txt", s).gains, 3.0);
}

TEST(CharacterScale, NoFactorsLeaveTheCharacterAsItWas) {
  const ScaledCharacter out = scale_deepmimic_character(kCharacter, "small.txt", {});
  EXPECT_DOUBLE_EQ(out.gains, 1.0);
  const DeepMimicCharacter a = parse_deepmimic_character(kCharacter, "a"), b = parse_deepmimic_character(out.character, "b");
  for (std::size_t j = 0; j < a.skeleton.joints.size(); ++j) {
    EXPECT_EQ(a.skeleton.joints[j].offset, b.skeleton.joints[j].offset);
    EXPECT_EQ(a.bodies[j].mass, b.bodies[j].mass);
    EXPECT_EQ(a.bodies[j].size, b.bodies[j].size);
  }
}

TEST(CharacterScale, BadInputIsNamed) {
  CharacterScaling s;
  s.lengths = {{"elbow", 1.2}};
  EXPECT_NE(error_of(s).find("no joint's name contains 'elbow'"), std::string::npos);
  s.lengths = {{"knee", 0}};
  EXPECT_NE(error_of(s).find("length factor of 'knee' must be a positive number"), std::string::npos);
  s.lengths = {};
  s.mass = -1;
  EXPECT_NE(error_of(s).find("mass factor"), std::string::npos);
  s.mass = 1;
  s.gains = std::nan("");
  EXPECT_NE(error_of(s).find("gain factor"), std::string::npos);
  s.gains = 0;
  // A malformed file: the parser's error, naming the file.
  EXPECT_NE(error_of(s, "{\"Skeleton\": 3}").find("small.txt"), std::string::npos);
  EXPECT_THROW((void)scale_deepmimic_controller("{}", "c.txt", 2), Error);
  EXPECT_THROW((void)scale_deepmimic_controller(kController, "c.txt", -2), Error);
}
