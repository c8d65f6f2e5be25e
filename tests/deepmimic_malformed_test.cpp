// Malformed DeepMimic character and motion files: every case must raise mimic::ParseError naming
// the source, the line and the problem, never another exception and never a crash. Each case
// mutates a small valid file.
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "malformed_cases.hpp"
#include "motion/deepmimic.hpp"

using namespace mimic;
using namespace mimic::test;

namespace {

const std::string kCharacterSource = "malformed_character.txt";
const std::string kMotionSource = "malformed_motion.txt";

// Four joints: the root, a spherical chest, a revolute knee and a fixed wrist; a body for each.
// One joint or body per line, so that every error about it is on that line.
const std::string kCharacter = R"({
"Skeleton": {
"Joints": [
{"ID": 0, "Name": "root", "Type": "none", "Parent": -1, "AttachX": 0, "AttachY": 0, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "TorqueLim": 0},
{"ID": 1, "Name": "chest", "Type": "spherical", "Parent": 0, "AttachX": 0, "AttachY": 0.21, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "LimLow0": -1, "LimHigh0": 1, "TorqueLim": 200},
{"ID": 2, "Name": "knee", "Type": "revolute", "Parent": 0, "AttachX": 0, "AttachY": -0.42, "AttachZ": 0.08, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "LimLow0": -3, "LimHigh0": 0, "TorqueLim": 150},
{"ID": 3, "Name": "wrist", "Type": "fixed", "Parent": 1, "AttachX": 0.3, "AttachY": 0.05, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0.5, "IsEndEffector": 1}
]
},
"BodyDefs": [
{"ID": 0, "Name": "root", "Shape": "sphere", "Mass": 6, "AttachX": 0, "AttachY": 0, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "Param0": 0.2, "Param1": 0, "Param2": 0, "ColGroup": 1},
{"ID": 1, "Name": "chest", "Shape": "box", "Mass": 10, "AttachX": 0, "AttachY": 0.1, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "Param0": 0.2, "Param1": 0.3, "Param2": 0.1},
{"ID": 2, "Name": "knee", "Shape": "capsule", "Mass": 3, "AttachX": 0, "AttachY": -0.2, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "Param0": 0.09, "Param1": 0.31, "Param2": 0},
{"ID": 3, "Name": "wrist", "Shape": "sphere", "Mass": 1, "AttachX": 0.05, "AttachY": 0, "AttachZ": 0, "AttachThetaX": 0, "AttachThetaY": 0, "AttachThetaZ": 0, "Param0": 0.08, "Param1": 0, "Param2": 0, "EnableFallContact": 1}
]
}
)";

// A motion of that character: per row the duration, root position (3), root rotation (w x y z),
// chest rotation (w x y z) and the knee angle. The last row's duration is unused.
const std::string kMotion = R"({
"Loop": "wrap",
"Frames":
[
[0.5, 0, 0.8, 0, 1, 0, 0, 0, 1, 0, 0, 0, -0.5],
[0.5, 0.1, 0.81, 0, 1, 0, 0, 0, 0.8, 0.6, 0, 0, -0.6],
[0, 0.2, 0.82, 0, 1, 0, 0, 0, 0.6, 0, 0.8, 0, -0.7]
]
}
)";

// A line of the base text (1-based), whole with its newline, found by a unique fragment.
std::string line_with(const std::string& text, std::string_view fragment) {
  replace_once(text, fragment, "");
  const std::size_t at = text.find(fragment);
  const std::size_t begin = text.rfind('\n', at) + 1;  // npos + 1 == 0 on the first line
  return text.substr(begin, text.find('\n', at) + 1 - begin);
}

const std::string kGarbage("\x89PNG\r\n\x1a\n\0\0\0\rIHDR\xff\xfe{[\"", 21);

std::vector<MalformedCase> character_cases() {
  const std::string& b = kCharacter;
  return {
      {"empty file", "", 0, "expected a JSON object at the top level"},
      {"binary garbage", kGarbage, 3, "not valid JSON"},
      {"truncated in a joint", cut_before(b, "\"AttachZ\": 0.08"), 6, "not valid JSON"},
      {"top level is an array", "[" + b + "]", 1, "expected a JSON object at the top level"},
      {"\"Skeleton\" missing", replace_once(b, "\"Skeleton\"", "\"Skelton\""), 1, "character: missing \"Skeleton\""},
      {"\"Skeleton\" is not an object", replace_once(b, "\"Skeleton\": {", "\"Skeleton\": 3, \"Other\": {"), 2,
       "\"Skeleton\": expected an object"},
      {"\"Joints\" is not an array", replace_once(b, "\"Joints\": [", "\"Joints\": \"all\", \"Other\": ["), 3,
       "\"Skeleton\" \"Joints\": expected an array"},
      {"\"Joints\" is empty", "{\"Skeleton\": {\"Joints\": []}}", 1, "\"Joints\" is empty"},
      {"a joint is not an object", replace_once(b, line_with(b, "\"Name\": \"wrist\", \"Type\""), "\"wrist\"\n"), 7,
       "joint 3: expected an object"},
      {"joint \"Name\" missing", replace_once(b, "\"Name\": \"knee\", \"Type\"", "\"Type\""), 6,
       "joint 2: missing \"Name\""},
      {"joint \"Name\" is not a string", replace_once(b, "\"Name\": \"knee\", \"Type\"", "\"Name\": [\"knee\"], \"Type\""),
       6, "joint 2 \"Name\": expected a string"},
      {"duplicate joint name", replace_once(b, "\"Name\": \"knee\", \"Type\"", "\"Name\": \"chest\", \"Type\""), 6,
       "joint 2: duplicate joint name 'chest'"},
      {"joints not in ID order", replace_once(b, "\"ID\": 2, \"Name\": \"knee\", \"Type\"",
                                              "\"ID\": 5, \"Name\": \"knee\", \"Type\""),
       6, "joints must be listed in ID order"},
      {"\"ID\" is text", replace_once(b, "\"ID\": 1, \"Name\": \"chest\", \"Type\"", "\"ID\": \"one\", \"Name\": \"chest\", \"Type\""),
       5, "joint 1 \"ID\": expected a finite number"},
      {"unknown joint \"Type\"", replace_once(b, "\"revolute\"", "\"hinge\""), 6,
       "joint 2 ('knee'): unsupported \"Type\" 'hinge' (spherical, revolute, fixed)"},
      {"joint \"Type\" missing", replace_once(b, "\"Type\": \"fixed\", ", ""), 7, "joint 3 ('wrist'): missing \"Type\""},
      {"\"Parent\" is a later joint", replace_once(b, "\"Type\": \"fixed\", \"Parent\": 1", "\"Type\": \"fixed\", \"Parent\": 3"),
       7, "joint 3 ('wrist'): \"Parent\" must be -1 for the root or an earlier joint's ID"},
      {"fractional \"Parent\"", replace_once(b, "\"Type\": \"fixed\", \"Parent\": 1", "\"Type\": \"fixed\", \"Parent\": 0.5"),
       7, "\"Parent\" must be -1 for the root or an earlier joint's ID"},
      {"second joint with \"Parent\" -1", replace_once(b, "\"Type\": \"spherical\", \"Parent\": 0", "\"Type\": \"spherical\", \"Parent\": -1"),
       5, "joint 1: only the first joint may have \"Parent\" -1"},
      {"root with a parent", replace_once(b, "\"Parent\": -1", "\"Parent\": 0"), 4,
       "joint 0 ('root'): \"Parent\" must be -1"},
      {"\"AttachY\" is text", replace_once(b, "\"AttachY\": 0.21", "\"AttachY\": \"high\""), 5,
       "joint 1 ('chest') \"AttachY\": expected a finite number"},
      {"\"AttachZ\" is nan", replace_once(b, "\"AttachZ\": 0.08", "\"AttachZ\": nan"), 6,
       "joint 2 ('knee') \"AttachZ\": expected a finite number"},
      {"\"AttachThetaZ\" overflows a double", replace_once(b, "\"AttachThetaZ\": 0.5", "\"AttachThetaZ\": 1e999"), 7,
       "joint 3 ('wrist') \"AttachThetaZ\": expected a finite number"},
      {"\"AttachThetaX\" missing on a non-root joint",
       replace_once(b, "\"AttachY\": 0.21, \"AttachZ\": 0, \"AttachThetaX\": 0,", "\"AttachY\": 0.21, \"AttachZ\": 0,"), 5,
       "joint 1 ('chest'): missing \"AttachThetaX\""},
      {"negative \"TorqueLim\"", replace_once(b, "\"TorqueLim\": 150", "\"TorqueLim\": -150"), 6,
       "joint 2 ('knee'): negative \"TorqueLim\""},
      {"\"BodyDefs\" is not an array", replace_once(b, "\"BodyDefs\": [", "\"BodyDefs\": 4, \"Other\": ["), 10,
       "\"BodyDefs\": expected an array"},
      {"fewer bodies than joints", replace_once(b, line_with(b, "\"Shape\": \"box\""), ""), 10,
       "\"BodyDefs\" has 3 bodies for 4 joints"},
      {"negative \"Mass\"", replace_once(b, "\"Mass\": 3", "\"Mass\": -3"), 13, "body 2 ('knee'): \"Mass\" must be positive"},
      {"zero \"Mass\"", replace_once(b, "\"Mass\": 10", "\"Mass\": 0"), 12, "body 1 ('chest'): \"Mass\" must be positive"},
      {"body \"Shape\" missing", replace_once(b, "\"Shape\": \"box\", ", ""), 12, "body 1: missing \"Shape\""},
      {"unknown body \"Shape\"", replace_once(b, "\"capsule\"", "\"cone\""), 13,
       "body 2: unsupported \"Shape\" 'cone' (box, capsule, cylinder, sphere)"},
      {"negative body size", replace_once(b, "\"Param1\": 0.31", "\"Param1\": -0.31"), 13, "body 2: negative size \"Param\""},
      {"\"ColGroup\" out of integer range", replace_once(b, "\"ColGroup\": 1", "\"ColGroup\": 1e300"), 11,
       "body 0 \"ColGroup\": expected an integer"},
  };
}

std::vector<MalformedCase> motion_cases() {
  const std::string& b = kMotion;
  return {
      {"empty file", "", 0, "expected a JSON object at the top level"},
      {"binary garbage", kGarbage, 3, "not valid JSON"},
      {"truncated in a frame", cut_before(b, ", 0, 1, 0, 0, 0, 0.8"), 6, "not valid JSON"},
      {"top level is the frame array", cut_before(replace_once(b, "{\n\"Loop\": \"wrap\",\n\"Frames\":\n", ""), "}"), 1,
       "expected a JSON object at the top level"},
      {"\"Frames\" missing", replace_once(b, "\"Frames\"", "\"Frame\""), 1, "motion: missing \"Frames\""},
      {"\"Frames\" is not an array", replace_once(b, "\"Frames\":\n[", "\"Frames\": 3,\n\"Other\":\n["), 3,
       "motion \"Frames\": expected an array"},
      {"\"Frames\" is empty", "{\"Loop\": \"wrap\", \"Frames\": []}", 1, "\"Frames\" is empty"},
      {"a frame is not an array", replace_once(b, line_with(b, "0.81"), "7,\n"), 6, "frame 1: expected an array of numbers"},
      {"frame with too few values", replace_once(b, ", -0.6]", "]"), 6,
       "frame 1: has 12 values, the character needs 13"},
      {"frame with too many values", replace_once(b, "-0.7]", "-0.7, 0]"), 7,
       "frame 2: has 14 values, the character needs 13"},
      {"joint type mismatch: a quaternion for the revolute knee", replace_once(b, "-0.5]", "1, 0, 0, 0]"), 5,
       "frame 0: has 16 values, the character needs 13"},
      {"value is text", replace_once(b, "0.81", "\"high\""), 6, "frame 1 value 2: expected a finite number"},
      {"value is nan", replace_once(b, "0.82", "nan"), 7, "frame 2 value 2: expected a finite number"},
      {"value overflows a double", replace_once(b, "0.1, 0.81", "1e999, 0.81"), 6,
       "frame 1 value 1: expected a finite number"},
      {"zero root quaternion", replace_once(b, "[0.5, 0, 0.8, 0, 1,", "[0.5, 0, 0.8, 0, 0,"), 5,
       "frame 0: rotation of 'root' is not a unit quaternion (norm 0.000000)"},
      {"chest quaternion of norm 2", replace_once(b, "0.8, 0.6, 0, 0", "1.6, 1.2, 0, 0"), 6,
       "frame 1: rotation of 'chest' is not a unit quaternion (norm 2.000000)"},
      {"zero duration in the first frame", replace_once(b, "[0.5, 0, 0.8", "[0, 0, 0.8"), 5,
       "frame 0: frame duration must be between 1e-6 and 10 s"},
      {"negative duration in a middle frame", replace_once(b, "[0.5, 0.1", "[-0.5, 0.1"), 6,
       "frame 1: frame duration must be between 1e-6 and 10 s"},
      {"duration over 10 s", replace_once(b, "[0.5, 0, 0.8", "[11, 0, 0.8"), 5,
       "frame 0: frame duration must be between 1e-6 and 10 s"},
      {"unknown \"Loop\" value", replace_once(b, "\"wrap\"", "\"forever\""), 2, "\"Loop\" must be \"wrap\" or \"none\""},
      {"\"Loop\" is not a string", replace_once(b, "\"wrap\"", "[\"wrap\"]"), 2, "\"Loop\" must be \"wrap\" or \"none\""},
      {"root position of 1e308", replace_once(b, "[0.5, 0.1, 0.81", "[0.5, 1e308, 0.81"), 6,
       "frame 1: root position is beyond 1e4 m of the origin (a unit or file error)"},
      {"a key given twice", replace_once(b, "\"Loop\": \"wrap\",", "\"Loop\": \"wrap\", \"Loop\": \"none\","), 2,
       "key 'Loop' is given twice (first on line 2)"},
  };
}

Skeleton character_skeleton() { return parse_deepmimic_character(kCharacter, kCharacterSource).skeleton; }

}  // namespace

TEST(DeepMimicMalformed, BaseTextsParse) {
  const DeepMimicCharacter ch = parse_deepmimic_character(kCharacter, kCharacterSource);
  ASSERT_EQ(ch.skeleton.num_joints(), 4);
  EXPECT_EQ(ch.skeleton.joints[1].type, JointType::Spherical);
  EXPECT_EQ(ch.skeleton.joints[2].type, JointType::Revolute);
  EXPECT_EQ(ch.skeleton.joints[3].type, JointType::Fixed);
  EXPECT_EQ(ch.bodies.size(), 4u);
  const Clip clip = parse_deepmimic_motion(kMotion, kMotionSource, ch.skeleton);
  EXPECT_EQ(clip.num_frames(), 3);
  EXPECT_EQ(clip.loop, LoopMode::Wrap);
  EXPECT_NEAR(clip.fps, 2.0, 1e-12);
}

TEST(DeepMimicMalformed, EveryCharacterCaseRaisesParseErrorWithLineAndMessage) {
  const std::vector<MalformedCase> table = character_cases();
  EXPECT_GE(table.size(), 15u);
  expect_parse_errors(table, kCharacter, kCharacterSource,
                      [](const std::string& text) { parse_deepmimic_character(text, kCharacterSource); });
}

TEST(DeepMimicMalformed, EveryMotionCaseRaisesParseErrorWithLineAndMessage) {
  const Skeleton sk = character_skeleton();
  const std::vector<MalformedCase> table = motion_cases();
  EXPECT_GE(table.size(), 15u);
  expect_parse_errors(table, kMotion, kMotionSource,
                      [&sk](const std::string& text) { parse_deepmimic_motion(text, kMotionSource, sk); });
}
