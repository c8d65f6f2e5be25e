#include "motion/bvh.hpp"

#include <cmath>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/text_scanner.hpp"

namespace mimic {
namespace {

constexpr int kMaxJoints = 4096;
constexpr long kMaxFrames = 10'000'000;

struct Channel {
  int joint;
  bool position;  // else rotation
  char axis;      // 'X', 'Y' or 'Z'
};

struct JointChannels {
  std::string rot_order;                 // rotation axes, outermost first
  std::vector<int> rot_index, pos_index;  // index of each channel in a frame row
  std::string pos_axes;
};

class BvhParser {
 public:
  BvhParser(std::string_view text, const std::string& source, const AxisConvention& axes)
      : sc_(text, source), basis_(source_to_mimic(axes)), scale_(axes.scale) {}

  Clip parse() {
    sc_.expect_word("HIERARCHY");
    parse_hierarchy();
    parse_motion();
    clip_.skeleton.validate();
    return std::move(clip_);
  }

 private:
  Vec3 to_mimic(const Vec3& v) const { return basis_ * (v * scale_); }

  Vec3 read_offset() {
    sc_.expect_word("OFFSET");
    Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = sc_.expect_double("an OFFSET coordinate");
    return v;
  }

  void read_channels(int joint) {
    sc_.expect_word("CHANNELS");
    const long n = sc_.expect_int("the number of channels");
    if (n < 0 || n > 6) sc_.fail("a joint has 0 to 6 channels, found " + std::to_string(n));
    JointChannels& jc = chans_[static_cast<std::size_t>(joint)];
    for (long k = 0; k < n; ++k) {
      const std::string_view t = sc_.expect_token("a channel name");
      if (t.size() != 9 || (t.substr(1) != "position" && t.substr(1) != "rotation") ||
          std::string_view("XYZ").find(t[0]) == std::string_view::npos)
        sc_.fail("unknown channel '" + printable_token(t) + "' (expected Xposition..Zrotation)");
      const bool pos = t.substr(1) == "position";
      std::string& axes = pos ? jc.pos_axes : jc.rot_order;
      if (axes.find(t[0]) != std::string::npos) sc_.fail("channel '" + std::string(t) + "' is listed twice");
      axes += t[0];
      (pos ? jc.pos_index : jc.rot_index).push_back(num_channels_++);
    }
  }

  void parse_hierarchy() {
    // Iterative descent (no recursion) so that deeply nested input cannot exhaust the stack.
    std::vector<int> stack;  // open joints; -2 marks an open End Site
    sc_.expect_word("ROOT");
    open_joint(-1, stack);
    while (!stack.empty()) {
      const std::string_view t = sc_.expect_token("JOINT, End Site or '}'");
      if (t == "}") {
        stack.pop_back();
      } else if (t == "JOINT") {
        if (stack.back() < 0) sc_.fail("a JOINT cannot be inside an End Site");
        open_joint(stack.back(), stack);
      } else if (t == "End") {
        if (stack.back() < 0) sc_.fail("an End Site cannot be inside an End Site");
        sc_.expect_word("Site");
        sc_.expect_word("{");
        const int parent = stack.back();
        Site s;
        s.joint = parent;
        s.name = clip_.skeleton.joints[static_cast<std::size_t>(parent)].name + "_end";
        s.offset = to_mimic(read_offset());
        if (clip_.skeleton.find_site(s.name) >= 0) s.name += std::to_string(clip_.skeleton.sites.size());
        clip_.skeleton.sites.push_back(s);
        stack.push_back(-2);
      } else if (t == "ROOT") {
        sc_.fail("only one ROOT is supported");
      } else {
        sc_.fail("expected JOINT, End Site or '}', found '" + printable_token(t) + "'");
      }
    }
  }

  void open_joint(int parent, std::vector<int>& stack) {
    if (clip_.skeleton.num_joints() >= kMaxJoints) sc_.fail("more than " + std::to_string(kMaxJoints) + " joints");
    Joint j;
    j.name = std::string(sc_.expect_token("a joint name"));
    if (j.name == "{") sc_.fail("joint name missing before '{'");
    if (clip_.skeleton.find(j.name) >= 0) sc_.fail("duplicate joint name '" + printable_token(j.name) + "'");
    j.parent = parent;
    joint_lines_.push_back(sc_.line());
    sc_.expect_word("{");
    j.offset = to_mimic(read_offset());
    const int index = clip_.skeleton.num_joints();
    chans_.emplace_back();
    read_channels(index);
    const JointChannels& jc = chans_.back();
    if (parent < 0) {
      j.type = JointType::Free;
    } else if (jc.rot_order.size() == 1) {
      j.type = JointType::Revolute;
      j.axis = basis_ * axis_vector(jc.rot_order[0]);
    } else {
      j.type = jc.rot_order.empty() ? JointType::Fixed : JointType::Spherical;
    }
    clip_.skeleton.joints.push_back(std::move(j));
    stack.push_back(index);
  }

  void parse_motion() {
    sc_.expect_word("MOTION");
    sc_.expect_word("Frames:");
    const long frames = sc_.expect_int("the frame count");
    const int frames_line = sc_.line();
    if (frames < 1 || frames > kMaxFrames) sc_.fail("frame count must be 1.." + std::to_string(kMaxFrames));
    if (frames * clip_.skeleton.num_joints() > kMaxClipRotations)
      sc_.fail("clip too large: " + std::to_string(frames) + " frames of " + std::to_string(clip_.skeleton.num_joints()) +
               " joints exceed " + std::to_string(kMaxClipRotations) + " joint rotations");
    sc_.expect_word("Frame");
    sc_.expect_word("Time:");
    const double dt = sc_.expect_double("the frame time");
    if (!(dt > 1e-6) || dt > 10.0) sc_.fail("frame time must be between 1e-6 and 10 seconds");
    clip_.fps = 1.0 / dt;
    clip_.loop = LoopMode::None;
    sc_.rest_of_line();

    const std::size_t nj = clip_.skeleton.joints.size();
    std::vector<double> row(static_cast<std::size_t>(num_channels_));
    const Quat basis_inv = basis_.conjugate();
    std::vector<Vec3> first_pos(nj, Vec3::Zero());  // non-root position channels, frame 0
    for (long f = 0; f < frames; ++f) {
      if (sc_.at_end())
        sc_.fail_at(frames_line, "file ends after " + std::to_string(f) + " frames, 'Frames:' says " + std::to_string(frames));
      const int line = sc_.line();
      for (int c = 0; c < num_channels_; ++c) {
        if (sc_.at_end() || sc_.line() != line)  // at_end() first: it skips to the next token's line
          sc_.fail_at(line, "frame " + std::to_string(f) + " has " + std::to_string(c) + " values, expected " +
                                std::to_string(num_channels_));
        row[static_cast<std::size_t>(c)] = sc_.expect_double("a channel value");
      }
      if (!sc_.at_end() && sc_.line() == line)
        sc_.fail_at(line, "frame " + std::to_string(f) + " has more than " + std::to_string(num_channels_) + " values");
      Pose p = rest_pose(clip_.skeleton);
      for (std::size_t j = 0; j < nj; ++j) {
        const JointChannels& jc = chans_[j];
        double angles[3] = {0, 0, 0};
        for (std::size_t k = 0; k < jc.rot_order.size(); ++k) {
          const double degrees = row[static_cast<std::size_t>(jc.rot_index[k])];
          if (std::abs(degrees) > kMaxAngleDegrees)
            sc_.fail_at(line, "frame " + std::to_string(f) + ": joint '" + clip_.skeleton.joints[j].name + "' turns " + std::to_string(degrees) +
                                  " degrees, beyond 1e6 (a unit or file error)");
          angles[k] = deg_to_rad(degrees);
        }
        const Quat q_src = euler_intrinsic(jc.rot_order, angles);
        const Quat q = canonical((basis_ * q_src * basis_inv).normalized());
        Vec3 pos_src = Vec3::Zero();
        for (std::size_t k = 0; k < jc.pos_axes.size(); ++k)
          pos_src += axis_vector(jc.pos_axes[k]) * row[static_cast<std::size_t>(jc.pos_index[k])];
        if (j == 0) {
          p.rot[0] = q;
          p.root_pos = clip_.skeleton.joints[0].offset + to_mimic(pos_src);
          if (!plausible_position(p.root_pos))
            sc_.fail_at(line, "frame " + std::to_string(f) + ": root position is beyond 1e4 m of the origin (a unit or file error)");
        } else {
          p.rot[j] = q;
          check_fixed_translation(j, f, line, pos_src, first_pos);
        }
      }
      clip_.frames.push_back(std::move(p));
    }
    if (!sc_.at_end()) sc_.fail("unexpected data after the last frame ('Frames: " + std::to_string(frames) + "')");
    if (clip_.skeleton.joints[0].offset.norm() > 0) clip_.skeleton.joints[0].offset = Vec3::Zero();
  }

  // Position channels on non-root joints are accepted when they never change: they are the bone.
  void check_fixed_translation(std::size_t j, long f, int line, const Vec3& pos_src, std::vector<Vec3>& first) {
    const JointChannels& jc = chans_[j];
    if (jc.pos_axes.empty()) return;
    if (f == 0) {
      first[j] = pos_src;
      clip_.skeleton.joints[j].offset = to_mimic(pos_src);
      return;
    }
    if ((pos_src - first[j]).norm() > 1e-6 * (1.0 + first[j].norm()))
      sc_.fail_at(line, "joint '" + clip_.skeleton.joints[j].name +
                            "' translates over time; only the root may (bone lengths are fixed)");
  }

  TextScanner sc_;
  Quat basis_;
  double scale_;
  Clip clip_;
  std::vector<JointChannels> chans_;
  std::vector<int> joint_lines_;
  int num_channels_ = 0;
};

}  // namespace

Clip parse_bvh(std::string_view text, const std::string& source, const AxisConvention& axes) {
  Clip c = BvhParser(text, source, axes).parse();
  c.name = std::filesystem::path(source).stem().string();
  return c;
}

Clip load_bvh(const std::filesystem::path& path, const AxisConvention& axes) {
  return parse_bvh(read_text_file(path), path.string(), axes);
}

}  // namespace mimic
