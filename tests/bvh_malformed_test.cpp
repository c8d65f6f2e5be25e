// Malformed BVH input: every case must raise mimic::ParseError naming the source, the line and
// the problem, never another exception and never a crash. Each case mutates a small valid file.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "malformed_cases.hpp"
#include "motion/bvh.hpp"

using namespace mimic;
using namespace mimic::test;

namespace {

const std::string kSource = "malformed.bvh";

// Three joints (free root, spherical Chest, revolute Elbow with an end site), 10 channels,
// 2 frames. The comments are line numbers.
const std::string kBase =
    "HIERARCHY\n"                                                                  // 1
    "ROOT Hips\n"                                                                  // 2
    "{\n"                                                                          // 3
    "  OFFSET 0 0 0\n"                                                             // 4
    "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"   // 5
    "  JOINT Chest\n"                                                              // 6
    "  {\n"                                                                        // 7
    "    OFFSET 0 10 0\n"                                                          // 8
    "    CHANNELS 3 Zrotation Xrotation Yrotation\n"                               // 9
    "    JOINT Elbow\n"                                                            // 10
    "    {\n"                                                                      // 11
    "      OFFSET 0 8 0\n"                                                         // 12
    "      CHANNELS 1 Xrotation\n"                                                 // 13
    "      End Site\n"                                                             // 14
    "      {\n"                                                                    // 15
    "        OFFSET 0 5 0\n"                                                       // 16
    "      }\n"                                                                    // 17
    "    }\n"                                                                      // 18
    "  }\n"                                                                        // 19
    "}\n"                                                                          // 20
    "MOTION\n"                                                                     // 21
    "Frames: 2\n"                                                                  // 22
    "Frame Time: 0.033333\n"                                                       // 23
    "0 90 0 0 0 0 10 20 30 40\n"                                                   // 24
    "1 90 0 5 0 0 15 25 35 45\n";                                                  // 25

std::vector<MalformedCase> cases() {
  const std::string& b = kBase;
  return {
      {"empty file", "", 1, "unexpected end of file, expected 'HIERARCHY'"},
      {"binary garbage", std::string("\x7f" "ELF\x02\x01\x01\0\0\0\xff\xfe\n\x90\x90", 15), 1,
       "expected 'HIERARCHY', found '?ELF"},
      {"misspelled HIERARCHY", replace_once(b, "HIERARCHY", "HIERACHY"), 1,
       "expected 'HIERARCHY', found 'HIERACHY'"},
      {"ROOT keyword missing", replace_once(b, "ROOT Hips", "Hips"), 2, "expected 'ROOT', found 'Hips'"},
      {"second ROOT", replace_once(b, "JOINT Chest", "ROOT Chest"), 6, "only one ROOT is supported"},
      {"root name missing", replace_once(b, "ROOT Hips", "ROOT"), 3, "joint name missing before '{'"},
      {"'{' missing after a joint name", replace_once(b, "JOINT Elbow\n    {\n", "JOINT Elbow\n"), 11,
       "expected '{', found 'OFFSET'"},
      {"duplicate joint name", replace_once(b, "JOINT Elbow", "JOINT Chest"), 10, "duplicate joint name 'Chest'"},
      {"unknown word in the hierarchy", replace_once(b, "JOINT Elbow", "JOIN Elbow"), 10,
       "expected JOINT, End Site or '}', found 'JOIN'"},
      {"OFFSET keyword missing", replace_once(b, "    OFFSET 0 10 0\n", ""), 8,
       "expected 'OFFSET', found 'CHANNELS'"},
      {"OFFSET with two coordinates", replace_once(b, "OFFSET 0 10 0", "OFFSET 0 10"), 9,
       "expected an OFFSET coordinate (a finite number), found 'CHANNELS'"},
      {"OFFSET coordinate is a word", replace_once(b, "OFFSET 0 8 0", "OFFSET 0 eight 0"), 12,
       "expected an OFFSET coordinate (a finite number), found 'eight'"},
      {"OFFSET coordinate is nan", replace_once(b, "OFFSET 0 0 0", "OFFSET nan 0 0"), 4,
       "expected an OFFSET coordinate (a finite number), found 'nan'"},
      {"End Site OFFSET overflows a double", replace_once(b, "OFFSET 0 5 0", "OFFSET 0 1e999 0"), 16,
       "found '1e999'"},
      {"CHANNELS keyword missing", replace_once(b, "    CHANNELS 3 Zrotation Xrotation Yrotation\n", ""), 9,
       "expected 'CHANNELS', found 'JOINT'"},
      {"seven channels", replace_once(b, "CHANNELS 6 Xposition", "CHANNELS 7 Xposition"), 5,
       "a joint has 0 to 6 channels, found 7"},
      {"negative channel count", replace_once(b, "CHANNELS 3", "CHANNELS -3"), 9,
       "a joint has 0 to 6 channels, found -3"},
      {"fractional channel count", replace_once(b, "CHANNELS 1 Xrotation", "CHANNELS 1.5 Xrotation"), 13,
       "expected the number of channels (an integer), found '1.5'"},
      {"unknown channel name", replace_once(b, "Zrotation Xrotation Yrotation\n    JOINT",
                                            "Zrotation Wrotation Yrotation\n    JOINT"),
       9, "unknown channel 'Wrotation'"},
      {"channel listed twice", replace_once(b, "CHANNELS 3 Zrotation Xrotation Yrotation",
                                            "CHANNELS 3 Zrotation Xrotation Zrotation"),
       9, "channel 'Zrotation' is listed twice"},
      {"fewer channel names than the count", replace_once(b, "CHANNELS 1 Xrotation", "CHANNELS 2 Xrotation"), 14,
       "unknown channel 'End'"},
      {"'End' without 'Site'", replace_once(b, "End Site", "End Sight"), 14, "expected 'Site', found 'Sight'"},
      {"JOINT inside an End Site", replace_once(b, "OFFSET 0 5 0\n", "OFFSET 0 5 0\n        JOINT Tip\n"), 17,
       "a JOINT cannot be inside an End Site"},
      {"End Site inside an End Site", replace_once(b, "OFFSET 0 5 0\n", "OFFSET 0 5 0\n        End Site\n"), 17,
       "an End Site cannot be inside an End Site"},
      {"closing brace missing", replace_once(b, "}\nMOTION", "MOTION"), 20,
       "expected JOINT, End Site or '}', found 'MOTION'"},
      {"extra closing brace", replace_once(b, "}\nMOTION", "}\n}\nMOTION"), 21, "expected 'MOTION', found '}'"},
      {"truncated inside the hierarchy", cut_before(b, "      CHANNELS 1"), 13,
       "unexpected end of file, expected 'CHANNELS'"},
      {"MOTION keyword missing", replace_once(b, "MOTION\n", ""), 21, "expected 'MOTION', found 'Frames:'"},
      {"'Frames' without colon", replace_once(b, "Frames: 2", "Frames 2"), 22, "expected 'Frames:', found 'Frames'"},
      {"zero frames", replace_once(b, "Frames: 2", "Frames: 0"), 22, "frame count must be 1..10000000"},
      {"frame count is a word", replace_once(b, "Frames: 2", "Frames: two"), 22,
       "expected the frame count (an integer), found 'two'"},
      {"frame count overflows", replace_once(b, "Frames: 2", "Frames: 99999999999999999999"), 22,
       "expected the frame count (an integer), found '99999999999999999999'"},
      {"'Frame Time' line missing", replace_once(b, "Frame Time: 0.033333\n", ""), 23,
       "expected 'Frame', found '0'"},
      {"zero frame time", replace_once(b, "Frame Time: 0.033333", "Frame Time: 0"), 23,
       "frame time must be between 1e-6 and 10 seconds"},
      {"negative frame time", replace_once(b, "Frame Time: 0.033333", "Frame Time: -0.033333"), 23,
       "frame time must be between 1e-6 and 10 seconds"},
      {"infinite frame time", replace_once(b, "Frame Time: 0.033333", "Frame Time: inf"), 23,
       "expected the frame time (a finite number), found 'inf'"},
      {"channel value is a word", replace_once(b, "0 0 10 20", "0 0 ten 20"), 24,
       "expected a channel value (a finite number), found 'ten'"},
      {"channel value is nan", replace_once(b, "15 25 35 45", "15 nan 35 45"), 25,
       "expected a channel value (a finite number), found 'nan'"},
      {"last frame has too few values", replace_once(b, "15 25 35 45", "15 25 35"), 25,
       "frame 1 has 9 values, expected 10"},
      {"first frame has too few values", replace_once(b, "10 20 30 40", "10 20 30"), 24,
       "frame 0 has 9 values, expected 10"},
      {"first frame has too many values", replace_once(b, "10 20 30 40", "10 20 30 40 50"), 24,
       "frame 0 has more than 10 values"},
      {"fewer frames than announced", replace_once(b, "Frames: 2", "Frames: 3"), 22,
       "file ends after 2 frames, 'Frames:' says 3"},
      {"more frames than announced", replace_once(b, "Frames: 2", "Frames: 1"), 25,
       "unexpected data after the last frame ('Frames: 1')"},
      {"truncated in the middle of a frame", cut_before(b, " 0 0 15 25"), 25, "frame 1 has 4 values, expected 10"},
      {"root position of 1e308 (finite, and written out as such before)", replace_once(b, "1 90 0 5", "1e308 90 0 5"), 25,
       "frame 1: root position is beyond 1e4 m of the origin (a unit or file error)"},
      {"an angle of -1e308 degrees (infinite in radians; found by the fuzzer)", replace_once(b, "1 90 0 5 0 0", "1 90 0 5 0 -1e308"), 25,
       "frame 1: joint 'Hips' turns -"},
      {"non-root joint translates over time",
       replace_once(replace_once(replace_once(b, "CHANNELS 1 Xrotation", "CHANNELS 2 Yposition Xrotation"),
                                 "10 20 30 40", "10 20 30 8 40"),
                    "15 25 35 45", "15 25 35 9 45"),
       25, "joint 'Elbow' translates over time"},
  };
}

Clip parse(const std::string& text) { return parse_bvh(text, kSource); }

}  // namespace

TEST(BvhMalformed, BaseTextParses) {
  const Clip clip = parse(kBase);
  EXPECT_EQ(clip.num_frames(), 2);
  EXPECT_EQ(clip.skeleton.num_joints(), 3);
  EXPECT_EQ(clip.skeleton.joints[1].type, JointType::Spherical);
  EXPECT_EQ(clip.skeleton.joints[2].type, JointType::Revolute);
  EXPECT_NEAR(clip.fps, 1.0 / 0.033333, 1e-9);
  // Constant position channels on a non-root joint are accepted: they are the bone.
  const std::string fixed_translation = replace_once(
      replace_once(replace_once(kBase, "CHANNELS 1 Xrotation", "CHANNELS 2 Yposition Xrotation"), "10 20 30 40",
                   "10 20 30 8 40"),
      "15 25 35 45", "15 25 35 8 45");
  EXPECT_EQ(parse(fixed_translation).num_frames(), 2);
}

TEST(BvhMalformed, EveryCaseRaisesParseErrorWithLineAndMessage) {
  const std::vector<MalformedCase> table = cases();
  EXPECT_GE(table.size(), 30u);
  expect_parse_errors(table, kBase, kSource, [](const std::string& text) { parse(text); });
}
