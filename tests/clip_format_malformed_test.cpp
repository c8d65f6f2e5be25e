// Malformed native clips (".mclip"): every case must raise mimic::ParseError naming the source,
// the line and the problem, never another exception and never a crash. Each case mutates the
// text write_clip produces for a small hand-made clip.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "malformed_cases.hpp"
#include "motion/clip_io.hpp"

using namespace mimic;
using namespace mimic::test;

namespace {

const std::string kSource = "malformed.mclip";

// A free root, a spherical spine and a revolute elbow (limits, torque limit, end effector), a
// site on the elbow, 2 frames.
Clip small_clip() {
  Clip c;
  c.name = "wave";
  c.fps = 30;
  c.loop = LoopMode::Wrap;
  Joint root;
  root.name = "root";
  root.type = JointType::Free;
  Joint spine;
  spine.name = "spine";
  spine.parent = 0;
  spine.type = JointType::Spherical;
  spine.offset = Vec3(0, 0, 0.3);
  spine.limits = {{-1, 1}, {-0.5, 0.5}, {-0.25, 0.25}};
  Joint elbow;
  elbow.name = "elbow";
  elbow.parent = 1;
  elbow.type = JointType::Revolute;
  elbow.offset = Vec3(0.25, 0, 0.1);
  elbow.axis = Vec3::UnitY();
  elbow.limits = {{-2, 0}};
  elbow.torque_limit = 40;
  elbow.end_effector = true;
  c.skeleton.joints = {root, spine, elbow};
  c.skeleton.sites = {Site{"hand", 2, Vec3(0.2, 0, 0)}};
  Pose p0 = rest_pose(c.skeleton, Vec3(0, 0, 1));
  Pose p1 = rest_pose(c.skeleton, Vec3(0.125, 0, 1));
  p1.rot[1] = Quat(0.8, 0.6, 0, 0);
  p1.rot[2] = Quat(0.6, 0, 0.8, 0);
  c.frames = {p0, p1};
  return c;
}

// What write_clip makes of it (checked by the positive test), line by line:
//  1-2  comments        3 format      4 version    5 name     6 fps      7 loop     8 frames
//  9    joints:        10 root       11 spine     12 elbow   13 sites:  14 hand
// 15    ---            16 frame 0: "0 0 1 1 0 0 0 1 0 0 0 1 0 0 0"
// 17    frame 1: "0.125 0 1 1 0 0 0 0.8 0.6 0 0 0.6 0 0.8 0"
const std::string& base_text() {
  static const std::string text = write_clip(small_clip());
  return text;
}

std::vector<MalformedCase> cases() {
  const std::string& b = base_text();
  const std::string row0 = "0 0 1 1 0 0 0 1 0 0 0 1 0 0 0\n";
  const std::string row1 = "0.125 0 1 1 0 0 0 0.8 0.6 0 0 0.6 0 0.8 0\n";
  return {
      {"empty file", "", 0, "not a mimic clip: no '---' line ends the header"},
      {"header without '---' (truncated)", cut_before(b, "---\n"), 0, "no '---' line ends the header"},
      {"binary garbage header", std::string("\x1f\x8b\x08\0\xde\xad\xbe\xef\n\0\x01\x02\n---\n\x80\n", 19), 1,
       "header is not valid YAML"},
      {"header is a YAML list", "- format\n- version\n---\n0 0 0 1 0 0 0\n", 1, "header is not a YAML mapping"},
      {"header is not valid YAML", replace_once(b, "limits: [[-2, 0]]", "limits: [[-2, 0]"), 12,
       "header is not valid YAML"},
      {"'format' missing", replace_once(b, "format: mimic-clip\n", ""), 3, "header: missing 'format'"},
      {"wrong 'format'", replace_once(b, "format: mimic-clip", "format: mimic-clap"), 3, "'format' must be mimic-clip"},
      {"unsupported version", replace_once(b, "version: 1", "version: 2"), 4,
       "version 2 is not supported (this build reads 1)"},
      {"fractional version", replace_once(b, "version: 1", "version: 1.5"), 4, "version: expected an integer"},
      {"'fps' missing", replace_once(b, "fps: 30\n", ""), 3, "header: missing 'fps'"},
      {"zero fps", replace_once(b, "fps: 30", "fps: 0"), 6, "fps must be positive"},
      {"negative fps", replace_once(b, "fps: 30", "fps: -30"), 6, "fps must be positive"},
      {"fps is nan", replace_once(b, "fps: 30", "fps: nan"), 6, "fps: expected a finite number"},
      {"fps overflows a double", replace_once(b, "fps: 30", "fps: 1e999"), 6, "fps: expected a finite number"},
      {"unknown loop mode", replace_once(b, "loop: wrap", "loop: forever"), 7, "loop must be wrap or none"},
      {"zero frames", replace_once(b, "frames: 2", "frames: 0"), 8, "frames must be between 1 and 10,000,000"},
      {"frame count is a word", replace_once(b, "frames: 2", "frames: two"), 8, "frames: expected an integer"},
      {"'joints' missing", replace_once(b, "joints:\n", "bones:\n"), 3, "header: missing 'joints'"},
      {"'joints' is empty", replace_once(b, "joints:\n", "joints: []\nbones:\n"), 9, "joints: expected a non-empty list"},
      {"a joint is not a mapping", replace_once(b, "  - {name: \"spine\"", "  - spine\n  - {name: \"spine\""), 11,
       "joint 1: expected a mapping"},
      {"joint name missing", replace_once(b, "{name: \"spine\", ", "{"), 11, "joint 1: missing 'name'"},
      {"duplicate joint name", replace_once(b, "name: \"elbow\"", "name: \"spine\""), 12,
       "joint 2: duplicate joint name 'spine'"},
      {"parent is a later joint", replace_once(b, "parent: 1,", "parent: 5,"), 12,
       "joint 2: parent must be -1 or an earlier joint"},
      {"non-root joint with parent -1", replace_once(b, "parent: 0,", "parent: -1,"), 11,
       "joint 1: only joint 0, the root, has parent -1"},
      {"unknown joint type", replace_once(b, "type: spherical", "type: ball"), 11,
       "joint 1: type must be free, spherical, revolute or fixed"},
      {"root is not free", replace_once(b, "type: free", "type: fixed"), 10, "joint 0: the root must be a free joint"},
      {"second free joint", replace_once(b, "type: spherical", "type: free"), 11,
       "joint 1: only the root (joint 0) may be a free joint"},
      {"offset with two numbers", replace_once(b, "offset: [0, 0, 0.3]", "offset: [0, 0.3]"), 11,
       "joint 1 offset: expected a list of 3 numbers"},
      {"offset value is a word", replace_once(b, "offset: [0, 0, 0.3]", "offset: [0, 0, high]"), 11,
       "joint 1 offset: expected a finite number"},
      {"zero rest quaternion", replace_once(b, "rest: [1, 0, 0, 0], axis", "rest: [0, 0, 0, 0], axis"), 12,
       "joint 2: rest is not a unit quaternion"},
      {"revolute axis missing", replace_once(b, "axis: [0, 1, 0], ", ""), 12, "joint 2: missing 'axis'"},
      {"zero revolute axis", replace_once(b, "axis: [0, 1, 0]", "axis: [0, 0, 0]"), 12,
       "joint 2: axis is not a unit vector"},
      {"lower limit above upper", replace_once(b, "limits: [[-2, 0]]", "limits: [[0, -2]]"), 12,
       "joint 2: a lower limit exceeds its upper limit"},
      {"negative torque limit", replace_once(b, "torque_limit: 40", "torque_limit: -40"), 12,
       "joint 2: torque_limit is negative"},
      {"end_effector is not a boolean", replace_once(b, "end_effector: true", "end_effector: maybe"), 12,
       "joint 2: end_effector must be true or false"},
      {"'sites' is not a list", replace_once(b, "sites:\n", "sites: 5\nother:\n"), 13, "sites: expected a list"},
      {"site on a missing joint", replace_once(b, "joint: 2", "joint: 3"), 14, "site 0: joint index out of range"},
      {"frame with too few values", replace_once(b, row1, "0.125 0 1 1 0 0 0 0.8 0.6 0 0 0.6 0 0.8\n"), 17,
       "frame 1 has 14 values, expected 15"},
      {"frame with too many values", replace_once(b, row0, "0 0 1 1 0 0 0 1 0 0 0 1 0 0 0 0\n"), 16,
       "frame 0 has more than 15 values"},
      {"frame value is a word", replace_once(b, "0.125", "abc"), 17,
       "expected a frame value (a finite number), found 'abc'"},
      {"frame value is nan", replace_once(b, row0, "0 0 nan 1 0 0 0 1 0 0 0 1 0 0 0\n"), 16,
       "expected a frame value (a finite number), found 'nan'"},
      {"frame value overflows a double", replace_once(b, "0.125", "1e999"), 17,
       "expected a frame value (a finite number), found '1e999'"},
      {"zero quaternion in a frame", replace_once(b, "0.8 0.6 0 0", "0 0 0 0"), 17,
       "frame 1: rotation of joint 'spine' is not a unit quaternion"},
      {"fewer frame rows than the header says", replace_once(b, "frames: 2", "frames: 3"), 8,
       "file ends after 2 frames, the header says 3"},
      {"more frame rows than the header says", replace_once(b, "frames: 2", "frames: 1"), 17,
       "more frame rows than the header's frames: 1"},
      {"truncated in the middle of a frame", cut_before(b, " 0.6 0 0.8 0"), 17, "frame 1 has 11 values, expected 15"},
  };
}

Clip parse(const std::string& text) { return parse_clip(text, kSource); }

}  // namespace

TEST(ClipFormatMalformed, BaseTextParses) {
  const std::string& text = base_text();
  const Clip clip = parse(text);
  EXPECT_EQ(clip.num_frames(), 2);
  EXPECT_EQ(clip.skeleton.num_joints(), 3);
  EXPECT_EQ(clip.name, "wave");
  EXPECT_EQ(clip.loop, LoopMode::Wrap);
  EXPECT_TRUE(clip.skeleton.joints[2].end_effector);
  // The layout the table relies on.
  EXPECT_NE(text.find("\nfps: 30\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n---\n0 0 1 1 0 0 0 1 0 0 0 1 0 0 0\n0.125 0 1 1 0 0 0 0.8 0.6 0 0 0.6 0 0.8 0\n"),
            std::string::npos)
      << text;
}

TEST(ClipFormatMalformed, EveryCaseRaisesParseErrorWithLineAndMessage) {
  const std::vector<MalformedCase> table = cases();
  EXPECT_GE(table.size(), 30u);
  expect_parse_errors(table, base_text(), kSource, [](const std::string& text) { parse(text); });
}
