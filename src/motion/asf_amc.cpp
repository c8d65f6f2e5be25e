// Acclaim ASF/AMC import. Each bone's joint frame is F_i = R_i * C_i (R_i its global rotation,
// C_i its "axis"), so rest_i = C_parent^-1 * C_i and the pose rotation is the AMC's M_i; every
// rotation is conjugated by the source-to-mimic basis, which keeps those formulas valid.
#include "motion/asf_amc.hpp"

#include <cmath>
#include <unordered_map>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/text_scanner.hpp"

namespace mimic {
namespace {

constexpr std::size_t kMaxBones = 4096;
constexpr long kMaxFrames = 10'000'000;

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c;
  return out;
}

// Acclaim applies the first listed axis first, so the matrix is R_last * ... * R_first.
Quat acclaim_rotation(std::string_view axes, const double* angles_rad) {
  Quat q = Quat::Identity();
  for (std::size_t i = 0; i < axes.size(); ++i) q = axis_rotation(axes[i], angles_rad[i]) * q;
  return q.normalized();
}

bool is_rotation_dof(std::string_view d) { return d == "rx" || d == "ry" || d == "rz"; }
bool is_translation_dof(std::string_view d) { return d == "tx" || d == "ty" || d == "tz"; }

// Line-oriented reading on top of TextScanner ('#' comments; ':' starts a section keyword).
class LineReader {
 public:
  LineReader(std::string_view text, const std::string& source) : sc(text, source) { sc.set_comment_char('#'); }
  // True while the next token is on `line`.
  bool on_line(int line) { return !sc.at_end() && sc.line() == line; }
  bool at_section() { return sc.at_end() || sc.peek().front() == ':'; }
  std::string_view token_on(int line, const std::string& what) {
    if (!on_line(line)) sc.fail_at(line, "missing " + what);
    return sc.next();
  }
  double number_on(int line, const std::string& what) {
    const std::string_view t = token_on(line, what);
    double v = 0.0;
    if (!parse_double(t, v)) sc.fail_at(line, what + " must be a finite number, found '" + printable_token(t) + "'");
    return v;
  }
  void end_of_line(int line, const std::string& what) {
    if (on_line(line)) sc.fail_at(line, "unexpected '" + printable_token(sc.peek()) + "' after " + what);
  }
  TextScanner sc;
};

struct Bone {
  std::string name;
  int line = 0;  // of its 'begin'
  Vec3 dir = Vec3::Zero();
  double length = -1.0;  // < 0: not given
  double axis[3] = {0, 0, 0};
  std::string axis_order = "xyz";
  std::vector<std::string> dofs;
  std::vector<std::pair<double, double>> limits;  // in the file's angle unit
  int parent = -2;                                 // bone index, -1 = root, -2 = none yet
  int parent_line = 0;
  std::vector<int> children;
};

class AsfParser {
 public:
  AsfParser(std::string_view text, const std::string& source, const AxisConvention& axes)
      : r_(text, source), axes_(axes) {}

  AsfSkeleton parse() {
    if (r_.sc.at_end()) r_.sc.fail_at(0, "empty file");
    while (!r_.sc.at_end()) {
      const std::string_view key = r_.sc.next();
      const int line = r_.sc.line();
      if (key == ":version" || key == ":name" || key == ":documentation" || key == ":skin") {
        r_.sc.rest_of_line();
        while (!r_.at_section()) r_.sc.rest_of_line();  // free text up to the next keyword line
      } else if (key == ":units") {
        once(seen_units_, key, line);
        parse_units();
      } else if (key == ":root") {
        once(seen_root_, key, line);
        parse_root(line);
      } else if (key == ":bonedata") {
        once(seen_bonedata_, key, line);
        parse_bonedata();
      } else if (key == ":hierarchy") {
        once(seen_hierarchy_, key, line);
        if (!seen_bonedata_) r_.sc.fail_at(line, ":hierarchy must come after :bonedata");
        parse_hierarchy();
      } else {
        r_.sc.fail_at(line, (key[0] == ':' ? "unknown section '" : "expected a section keyword such as ':bonedata', found '") +
                                printable_token(key) + "'");
      }
    }
    for (const auto& [seen, name] : {std::pair{seen_root_, ":root"}, {seen_bonedata_, ":bonedata"}, {seen_hierarchy_, ":hierarchy"}})
      if (!seen) r_.sc.fail_at(0, std::string("missing '") + name + "' section");
    return build();
  }

 private:
  void once(bool& seen, std::string_view key, int line) {
    if (seen) r_.sc.fail_at(line, "duplicate '" + std::string(key) + "' section");
    seen = true;
  }

  std::string read_axis_order(int line, const std::string& who) {
    const std::string order = lower(r_.token_on(line, who + " axis order (e.g. XYZ)"));
    if (order.size() != 3 || order.find_first_not_of("xyz") != std::string::npos || order[0] == order[1] ||
        order[0] == order[2] || order[1] == order[2])
      r_.sc.fail_at(line, who + ": axis order '" + printable_token(order) + "' must be a permutation of XYZ");
    return order;
  }

  void parse_units() {
    while (!r_.at_section()) {
      const std::string_view key = r_.sc.next();
      const int line = r_.sc.line();
      if (key == "length") {
        length_unit_ = r_.number_on(line, ":units length");
        if (!(length_unit_ > 0.0)) r_.sc.fail_at(line, ":units length must be positive");
      } else if (key == "angle") {
        const std::string a = lower(r_.token_on(line, ":units angle (deg or rad)"));
        if (a != "deg" && a != "rad") r_.sc.fail_at(line, ":units angle must be 'deg' or 'rad', found '" + printable_token(a) + "'");
        degrees_ = a == "deg";
      } else if (key == "mass") {
        r_.number_on(line, ":units mass");
      } else {
        r_.sc.rest_of_line();  // other units do not affect the skeleton
        continue;
      }
      r_.end_of_line(line, ":units " + std::string(key));
    }
  }

  void parse_root(int section_line) {
    bool have_order = false;
    while (!r_.at_section()) {
      const std::string_view key = r_.sc.next();
      const int line = r_.sc.line();
      if (key == "order") {
        have_order = true;
        while (r_.on_line(line)) {
          const std::string d = lower(r_.sc.next());
          if (!is_rotation_dof(d) && !is_translation_dof(d))
            r_.sc.fail_at(line, "root: unknown channel '" + printable_token(d) + "' in order (expected TX TY TZ RX RY RZ)");
          for (const std::string& o : root_order_)
            if (o == d) r_.sc.fail_at(line, "root: channel '" + d + "' is listed twice in order");
          root_order_.push_back(d);
        }
      } else if (key == "axis") {
        root_axis_order_ = read_axis_order(line, "root");
      } else if (key == "position" || key == "orientation") {
        for (int k = 0; k < 3; ++k) {
          const double v = r_.number_on(line, "root " + std::string(key) + " coordinate");
          if (key == "orientation") root_orientation_[k] = v;
        }
      } else {
        r_.sc.fail_at(line, "root: unknown field '" + printable_token(key) + "' (expected order, axis, position, orientation)");
      }
      r_.end_of_line(line, "root " + std::string(key));
    }
    if (!have_order) r_.sc.fail_at(section_line, ":root has no 'order' line");
  }

  void parse_bonedata() {
    while (!r_.at_section()) {
      const std::string_view t = r_.sc.next();
      if (t != "begin") r_.sc.fail("expected 'begin' of a bone in :bonedata, found '" + printable_token(t) + "'");
      if (bones_.size() >= kMaxBones) r_.sc.fail("more than " + std::to_string(kMaxBones) + " bones");
      Bone b;
      b.line = r_.sc.line();
      r_.end_of_line(b.line, "'begin'");
      parse_bone(b);
      if (!bone_index_.emplace(b.name, static_cast<int>(bones_.size())).second)
        r_.sc.fail_at(b.line, "duplicate bone name '" + printable_token(b.name) + "'");
      bones_.push_back(std::move(b));
    }
  }

  void parse_bone(Bone& b) {
    bool have_dir = false;
    auto who = [&] { return b.name.empty() ? "bone at line " + std::to_string(b.line) : "bone '" + printable_token(b.name) + "'"; };
    for (;;) {
      if (r_.at_section() || r_.sc.peek() == "begin")
        r_.sc.fail_at(b.line, who() + ": 'begin' has no matching 'end'");
      const std::string_view key = r_.sc.next();
      const int line = r_.sc.line();
      if (key == "end") {
        r_.end_of_line(line, "'end'");
        break;
      } else if (key == "id" || key == "bodymass" || key == "cofmass") {
        r_.number_on(line, who() + " " + std::string(key));
      } else if (key == "name") {
        b.name = std::string(r_.token_on(line, "bone name"));
        long n = 0;
        if (b.name == "root" || b.name == "begin" || b.name == "end" || parse_long(b.name, n))
          r_.sc.fail_at(line, "'" + printable_token(b.name) + "' cannot be a bone name");
      } else if (key == "direction") {
        for (int k = 0; k < 3; ++k) b.dir[k] = r_.number_on(line, who() + " direction");
        const double n = b.dir.stableNorm();
        if (!(n > 1e-9) || !std::isfinite(n)) r_.sc.fail_at(line, who() + ": direction must be a non-zero vector");
        b.dir /= n;
        have_dir = true;
      } else if (key == "length") {
        b.length = r_.number_on(line, who() + " length");
        if (b.length < 0.0) r_.sc.fail_at(line, who() + ": length must not be negative");
      } else if (key == "axis") {
        for (double& a : b.axis) a = r_.number_on(line, who() + " axis angle");
        b.axis_order = read_axis_order(line, who());
      } else if (key == "dof") {
        if (!b.dofs.empty()) r_.sc.fail_at(line, who() + ": second 'dof' line");
        while (r_.on_line(line)) {
          const std::string d = lower(r_.sc.next());
          if (is_translation_dof(d) || d == "l")
            r_.sc.fail_at(line, who() + ": translational dof '" + d + "' is not supported (bones may only rotate: rx ry rz)");
          if (!is_rotation_dof(d)) r_.sc.fail_at(line, who() + ": unknown dof '" + printable_token(d) + "' (expected rx, ry, rz)");
          for (const std::string& o : b.dofs)
            if (o == d) r_.sc.fail_at(line, who() + ": dof '" + d + "' is listed twice");
          b.dofs.push_back(d);
        }
        if (b.dofs.empty()) r_.sc.fail_at(line, who() + ": 'dof' lists no channels");
      } else if (key == "limits") {
        parse_limits(b, line, who());
        continue;
      } else {
        r_.sc.fail_at(line, who() + ": unknown field '" + printable_token(key) + "'");
      }
      r_.end_of_line(line, who() + " " + std::string(key));
    }
    if (b.name.empty()) r_.sc.fail_at(b.line, "bone has no 'name'");
    if (!have_dir) r_.sc.fail_at(b.line, who() + " has no 'direction'");
    if (b.length < 0.0) r_.sc.fail_at(b.line, who() + " has no 'length'");
  }

  // One "(lo hi)" pair per dof, e.g. "(-160.0 , 20.0)", each on one line.
  void parse_limits(Bone& b, int line, const std::string& who) {
    if (b.dofs.empty()) r_.sc.fail_at(line, who + ": 'limits' before 'dof' (one limit pair per dof)");
    if (!b.limits.empty()) r_.sc.fail_at(line, who + ": second 'limits'");
    const std::size_t want = b.dofs.size();
    while (b.limits.size() < want || (!r_.sc.at_end() && r_.sc.peek().front() == '(')) {
      if (r_.sc.at_end() || r_.sc.peek().front() != '(' || b.limits.size() == want)
        r_.sc.fail_at(line, who + ": 'limits' needs one '(lo hi)' pair per dof (" + std::to_string(want) + "), found " +
                                (b.limits.size() == want ? "more" : std::to_string(b.limits.size())));
      const int pair_line = r_.sc.line();
      std::string text;
      while (r_.on_line(pair_line) && text.find(')') == std::string::npos && text.size() < 200) text += std::string(r_.sc.next()) + " ";
      if (text.find(')') == std::string::npos) r_.sc.fail_at(pair_line, who + ": limit pair '(lo hi)' has no ')'");
      for (char& c : text) c = (c == ',' || c == '(' || c == ')') ? ' ' : c;
      LineReader pair(text, r_.sc.source());
      double v[2] = {0, 0};
      for (double& x : v) {
        const std::string t = lower(pair.sc.next());
        if (t == "inf" || t == "+inf" || t == "-inf")  // the Acclaim spec allows unbounded limits
          x = (t[0] == '-' ? -1.0 : 1.0) * HUGE_VAL;
        else if (!parse_double(t, x))
          r_.sc.fail_at(pair_line, who + ": limit pair must be '(lo hi)' with finite numbers, found '" + printable_token(t) + "'");
      }
      if (!pair.sc.at_end()) r_.sc.fail_at(pair_line, who + ": a limit pair has more than two numbers");
      if (v[0] > v[1]) r_.sc.fail_at(pair_line, who + ": limit low is greater than high");
      b.limits.emplace_back(v[0], v[1]);
      r_.end_of_line(pair_line, who + " limit pair");
    }
  }

  void parse_hierarchy() {
    if (r_.at_section()) r_.sc.fail(":hierarchy needs 'begin'");
    r_.sc.expect_word("begin");
    const int begin_line = r_.sc.line();
    r_.end_of_line(begin_line, "'begin'");
    for (;;) {
      if (r_.at_section()) r_.sc.fail_at(begin_line, ":hierarchy 'begin' has no matching 'end'");
      const std::string_view name = r_.sc.next();
      const int line = r_.sc.line();
      if (name == "end") {
        r_.end_of_line(line, "'end'");
        return;
      }
      const int parent = find_bone(name, line);
      while (r_.on_line(line)) {
        const std::string_view cname = r_.sc.next();
        const int c = find_bone(cname, line);
        if (c < 0) r_.sc.fail_at(line, "'root' cannot be a child in :hierarchy");
        Bone& child = bones_[static_cast<std::size_t>(c)];
        if (child.parent != -2)
          r_.sc.fail_at(line, "bone '" + printable_token(child.name) + "' has two parents in :hierarchy (first given at line " +
                                  std::to_string(child.parent_line) + ")");
        child.parent = parent;
        child.parent_line = line;
        (parent < 0 ? root_children_ : bones_[static_cast<std::size_t>(parent)].children).push_back(c);
      }
    }
  }

  int find_bone(std::string_view name, int line) {
    if (name == "root") return -1;
    const auto it = bone_index_.find(std::string(name));
    if (it == bone_index_.end()) r_.sc.fail_at(line, "unknown bone '" + printable_token(name) + "' in :hierarchy");
    return it->second;
  }

  // Joints in breadth-first order from the root (iterative: no recursion on untrusted depth).
  std::vector<int> joint_order() {
    std::vector<int> order(root_children_.begin(), root_children_.end());
    for (std::size_t k = 0; k < order.size(); ++k)
      for (int c : bones_[static_cast<std::size_t>(order[k])].children) order.push_back(c);
    if (order.size() == bones_.size()) return order;
    std::vector<bool> reached(bones_.size(), false);
    for (int b : order) reached[static_cast<std::size_t>(b)] = true;
    for (std::size_t i = 0; i < bones_.size(); ++i) {
      if (reached[i]) continue;
      // Walk up: a bone that reaches one without a parent is cut off; otherwise it is in a cycle.
      int b = static_cast<int>(i);
      for (std::size_t step = 0; step <= bones_.size() && b >= 0; ++step) b = bones_[static_cast<std::size_t>(b)].parent;
      const Bone& bone = bones_[i];
      if (b == -2) r_.sc.fail_at(bone.line, "bone '" + printable_token(bone.name) + "' is not connected to the root in :hierarchy");
      r_.sc.fail_at(bone.parent_line, "bone '" + printable_token(bone.name) + "' is not connected to the root: its parents form a cycle in :hierarchy");
    }
    return order;
  }

  AsfSkeleton build() {
    AsfSkeleton out;
    out.source = r_.sc.source();
    out.degrees = degrees_;
    out.metres_per_unit = axes_.scale > 0.0 ? axes_.scale : 0.0254 / length_unit_;
    if (!std::isfinite(out.metres_per_unit) || !(out.metres_per_unit > 0.0))
      r_.sc.fail_at(0, "unusable length scale (metres per unit must be positive and finite)");
    AxisConvention basis_axes = axes_;
    basis_axes.scale = out.metres_per_unit;
    out.basis = source_to_mimic(basis_axes);
    const Quat B = out.basis;
    const double ang = degrees_ ? kPi / 180.0 : 1.0;
    auto axis_rot = [&](const std::string& order, const double* a) {  // C in mimic axes: B C B^-1
      const double rad[3] = {a[0] * ang, a[1] * ang, a[2] * ang};
      return (B * acclaim_rotation(order, rad) * B.conjugate()).normalized();
    };
    auto bone_vec = [&](const Bone& b) {
      const Vec3 v = B * (b.dir * (b.length * out.metres_per_unit));
      if (!v.allFinite()) r_.sc.fail_at(b.line, "bone '" + printable_token(b.name) + "' is too long");
      return v;
    };

    Skeleton& sk = out.skeleton;
    Joint root;
    root.name = "root";
    root.type = JointType::Free;
    sk.joints.push_back(root);
    out.dofs.push_back(root_order_);
    out.axis_rot.push_back(axis_rot(root_axis_order_, root_orientation_));

    const std::vector<int> order = joint_order();
    std::vector<int> joint_of(bones_.size(), 0);
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Bone& b = bones_[static_cast<std::size_t>(order[k])];
      joint_of[static_cast<std::size_t>(order[k])] = static_cast<int>(k) + 1;
      Joint j;
      j.name = b.name;
      j.parent = b.parent < 0 ? 0 : joint_of[static_cast<std::size_t>(b.parent)];
      const Quat c = axis_rot(b.axis_order, b.axis);
      const Quat cp_inv = out.axis_rot[static_cast<std::size_t>(j.parent)].conjugate();
      // F_i = R_i * C_i, so rest_i = C_parent^-1 * C_i and the bone's start is its parent's tip.
      j.rest = (cp_inv * c).normalized();
      if (b.parent >= 0) j.offset = cp_inv * bone_vec(bones_[static_cast<std::size_t>(b.parent)]);
      j.type = b.dofs.empty() ? JointType::Fixed : b.dofs.size() == 1 ? JointType::Revolute : JointType::Spherical;
      if (j.type == JointType::Revolute) j.axis = B * axis_vector(b.dofs[0][1]);
      if (!b.limits.empty()) {
        // Spherical limits are about the joint frame's x, y, z (B maps each source axis to a
        // signed mimic axis); a revolute joint's axis carries the sign already.
        if (j.type == JointType::Spherical) j.limits.assign(3, {0.0, 0.0});
        for (std::size_t d = 0; d < b.dofs.size(); ++d) {
          // An infinite limit becomes half a turn: every angle is within [-pi, pi].
          auto rad = [&](double v) { return std::isfinite(v) ? v * ang : std::copysign(kPi, v); };
          const double lo = rad(b.limits[d].first), hi = rad(b.limits[d].second);
          if (j.type == JointType::Revolute) {
            j.limits.emplace_back(lo, hi);
            continue;
          }
          const Vec3 a = B * axis_vector(b.dofs[d][1]);
          Eigen::Index i = 0;
          a.cwiseAbs().maxCoeff(&i);
          j.limits[static_cast<std::size_t>(i)] = a[i] > 0 ? std::pair{lo, hi} : std::pair{-hi, -lo};
        }
      }
      if (b.children.empty()) sk.sites.push_back(Site{b.name + "_end", static_cast<int>(k) + 1, c.conjugate() * bone_vec(b)});
      sk.joints.push_back(std::move(j));
      out.dofs.push_back(b.dofs);
      out.axis_rot.push_back(c);
    }
    try {
      sk.validate();
    } catch (const Error& e) {
      r_.sc.fail_at(0, e.what());
    }
    return out;
  }

  LineReader r_;
  AxisConvention axes_;
  bool seen_units_ = false, seen_root_ = false, seen_bonedata_ = false, seen_hierarchy_ = false;
  double length_unit_ = 1.0;
  bool degrees_ = true;
  std::vector<std::string> root_order_;
  std::string root_axis_order_ = "xyz";
  double root_orientation_[3] = {0, 0, 0};
  std::vector<Bone> bones_;
  std::unordered_map<std::string, int> bone_index_;
  std::vector<int> root_children_;
};

class AmcParser {
 public:
  AmcParser(std::string_view text, const std::string& source, const AsfSkeleton& asf, double fps)
      : r_(text, source), asf_(asf), fps_(fps) {}

  Clip parse() {
    check_asf();
    const std::size_t nj = asf_.skeleton.joints.size();
    std::vector<std::size_t> needed;  // joints that every frame must give
    for (std::size_t j = 0; j < nj; ++j) {
      index_.emplace(asf_.skeleton.joints[j].name, j);
      if (!asf_.dofs[j].empty()) needed.push_back(j);
    }
    bool degrees = asf_.degrees;
    while (!r_.sc.at_end() && r_.sc.peek().front() == ':') {
      const std::string_view t = r_.sc.next();
      const std::string kw = lower(t);
      if (kw == ":degrees" || kw == ":radians") degrees = kw == ":degrees";
      else if (kw != ":fully-specified") r_.sc.fail("unknown AMC keyword '" + printable_token(t) + "'");
      r_.end_of_line(r_.sc.line(), "'" + printable_token(t) + "'");
    }
    ang_ = degrees ? kPi / 180.0 : 1.0;
    if (r_.sc.at_end()) r_.sc.fail_at(0, "no frames (expected a frame number 1 after the header)");

    Clip clip;
    clip.name = std::filesystem::path(r_.sc.source()).stem().string();
    clip.skeleton = asf_.skeleton;
    clip.fps = fps_;
    clip.loop = LoopMode::None;
    std::vector<long> seen(nj, 0);  // frame number each joint was last given in
    for (long frame = 1; !r_.sc.at_end(); ++frame) {
      const std::string_view t = r_.sc.next();
      const int line = r_.sc.line();
      long number = 0;
      if (!parse_long(t, number)) r_.sc.fail_at(line, "expected frame number " + std::to_string(frame) + ", found '" + printable_token(t) + "'");
      if (number != frame)
        r_.sc.fail_at(line, "frame number " + std::to_string(number) + " where " + std::to_string(frame) +
                                " was expected (frames must be numbered 1, 2, 3, ...)");
      if (frame > kMaxFrames || frame * static_cast<long>(nj) > kMaxClipRotations)
        r_.sc.fail_at(line, "frame " + std::to_string(frame) + ": the clip is too large (at most " + std::to_string(kMaxFrames) +
                                " frames and " + std::to_string(kMaxClipRotations) + " joint rotations)");
      r_.end_of_line(line, "frame number " + std::to_string(frame));
      Pose p;
      p.rot.assign(nj, Quat::Identity());
      p.rot[0] = asf_.axis_rot[0];
      long unused = 0;
      while (!r_.sc.at_end() && !parse_long(r_.sc.peek(), unused)) read_bone(p, frame, seen);
      for (std::size_t j : needed)
        if (seen[j] != frame)
          r_.sc.fail_at(line, "frame " + std::to_string(frame) + ": bone '" + printable_token(asf_.skeleton.joints[j].name) + "' is missing");
      clip.frames.push_back(std::move(p));
    }
    return clip;
  }

 private:
  // The skeleton may be hand-made: reject inconsistencies instead of indexing out of range.
  void check_asf() {
    const std::size_t nj = asf_.skeleton.joints.size();
    bool ok = nj > 0 && asf_.dofs.size() == nj && asf_.axis_rot.size() == nj && std::isfinite(asf_.metres_per_unit);
    for (std::size_t j = 0; ok && j < nj; ++j)
      for (const std::string& d : asf_.dofs[j]) ok = ok && (is_rotation_dof(d) || (j == 0 && is_translation_dof(d)));
    if (!ok) r_.sc.fail_at(0, "the ASF skeleton is empty or inconsistent (joints, dofs and axis rotations differ)");
    if (!std::isfinite(fps_) || !(fps_ > 0.0)) r_.sc.fail_at(0, "frame rate must be a positive number");
  }

  void read_bone(Pose& p, long frame, std::vector<long>& seen) {
    const std::string_view name = r_.sc.next();
    const int line = r_.sc.line();
    auto where = [&] { return "frame " + std::to_string(frame) + ": bone '" + printable_token(name) + "'"; };
    const auto it = index_.find(name);
    if (it == index_.end()) r_.sc.fail_at(line, "frame " + std::to_string(frame) + ": unknown bone '" + printable_token(name) + "'");
    const std::size_t j = it->second;
    if (seen[j] == frame) r_.sc.fail_at(line, where() + " appears twice");
    seen[j] = frame;
    const std::vector<std::string>& dofs = asf_.dofs[j];
    std::string axes;
    double angles[3] = {0, 0, 0};
    Vec3 pos = Vec3::Zero();
    for (std::size_t k = 0; k < dofs.size(); ++k) {
      if (!r_.on_line(line))
        r_.sc.fail_at(line, where() + " has " + std::to_string(k) + " values, expected " + std::to_string(dofs.size()));
      const std::string_view t = r_.sc.next();
      double v = 0.0;
      if (!parse_double(t, v)) r_.sc.fail_at(line, where() + ": value '" + printable_token(t) + "' is not a finite number");
      if (is_translation_dof(dofs[k])) {
        pos[dofs[k][1] - 'x'] = v;
      } else if (axes.size() < 3) {
        if (std::abs(v * ang_) > kMaxAngleDegrees * kPi / 180.0)
          r_.sc.fail_at(line, where() + ": angle '" + printable_token(t) + "' turns beyond 1e6 degrees (a unit or file error)");
        angles[axes.size()] = v * ang_;
        axes += dofs[k][1];
      }
    }
    if (r_.on_line(line)) r_.sc.fail_at(line, where() + " has more than " + std::to_string(dofs.size()) + " values");
    const Quat m = (asf_.basis * acclaim_rotation(axes, angles) * asf_.basis.conjugate()).normalized();
    if (j == 0) {
      // F_root = R_root * C_root = C_root * M_root.
      p.rot[0] = canonical((asf_.axis_rot[0] * m).normalized());
      p.root_pos = asf_.basis * (pos * asf_.metres_per_unit);
      if (!plausible_position(p.root_pos)) r_.sc.fail_at(line, where() + ": position is beyond 1e4 m of the origin (a unit or file error)");
    } else {
      p.rot[j] = canonical(m);
    }
  }

  LineReader r_;
  const AsfSkeleton& asf_;
  double fps_;
  double ang_ = 1.0;
  std::unordered_map<std::string_view, std::size_t> index_;
};

}  // namespace

AxisConvention asf_default_axes() { return AxisConvention{"y", "z", 0.0}; }

AsfSkeleton parse_asf(std::string_view text, const std::string& source, const AxisConvention& axes) {
  return AsfParser(text, source, axes).parse();
}

AsfSkeleton load_asf(const std::filesystem::path& path, const AxisConvention& axes) {
  return parse_asf(read_text_file(path), path.string(), axes);
}

Clip parse_amc(std::string_view text, const std::string& source, const AsfSkeleton& asf, double fps) {
  return AmcParser(text, source, asf, fps).parse();
}

Clip load_amc(const std::filesystem::path& path, const AsfSkeleton& asf, double fps) {
  return parse_amc(read_text_file(path), path.string(), asf, fps);
}

std::filesystem::path guess_asf(const std::filesystem::path& amc_path) {
  namespace fs = std::filesystem;
  const fs::path dir = amc_path.parent_path();
  const std::string stem = amc_path.stem().string();
  std::error_code ec;
  if (const std::size_t cut = stem.find('_'); cut != std::string::npos && cut > 0) {
    const fs::path by_name = dir / (stem.substr(0, cut) + ".asf");
    if (fs::is_regular_file(by_name, ec)) return by_name;
  }
  fs::path only;
  int count = 0;
  for (fs::directory_iterator it(dir.empty() ? fs::path(".") : dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (lower(it->path().extension().string()) != ".asf" || !it->is_regular_file(ec)) continue;
    only = dir / it->path().filename();
    ++count;
  }
  return count == 1 ? only : fs::path();
}

}  // namespace mimic
