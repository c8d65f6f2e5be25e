#include "motion/deepmimic.hpp"


#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/text_scanner.hpp"
#include "core/yaml_reader.hpp"

namespace mimic {
namespace {

// The top-level JSON object of a DeepMimic file.
YAML::Node load_json_object(const YamlReader& js, std::string_view text) {
  YAML::Node root = js.parse(text, "not valid JSON");
  if (!root.IsMap()) js.fail(root, "expected a JSON object at the top level");
  return root;
}

const Quat& basis() {
  static const Quat q = Quat(Mat3{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}});  // x->x, y->z, z->-y
  return q;
}

Vec3 to_mimic(const Vec3& v) { return basis() * v; }
Quat rot_to_mimic(const Quat& q) { return canonical((basis() * q * basis().conjugate()).normalized()); }
Quat rot_to_deepmimic(const Quat& q) { return canonical((basis().conjugate() * q * basis()).normalized()); }

Quat deepmimic_euler(double x, double y, double z) {
  const double zyx[3] = {z, y, x};
  return euler_intrinsic("ZYX", zyx);
}

Vec3 read_vec(const YamlReader& js, const YAML::Node& obj, const char* prefix, const std::string& where) {
  Vec3 v;
  const char* axes[3] = {"X", "Y", "Z"};
  for (int k = 0; k < 3; ++k) v[k] = js.number(obj, (std::string(prefix) + axes[k]).c_str(), where);
  return v;
}

std::string fmt_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Frames of unequal durations (DeepMimic allows them) resampled to the shortest duration:
// linear root positions, slerp rotations, the end kept exactly.
Clip resample_irregular(const Clip& in, const std::vector<double>& times, double dt) {
  Clip out = in;
  const double total = times.back();
  const auto intervals = std::max(1L, std::lround(total / dt));
  if (static_cast<double>(intervals) * static_cast<double>(in.skeleton.joints.size()) > static_cast<double>(kMaxClipRotations))
    throw Error("frame durations from " + fmt_number(dt) + " s to a total of " + fmt_number(total) +
                " s would need more than " + std::to_string(kMaxClipRotations) + " joint rotations at a constant rate");
  out.fps = static_cast<double>(intervals) / total;
  out.frames.clear();
  std::size_t seg = 0;
  for (long k = 0; k <= intervals; ++k) {
    const double t = std::min(total, static_cast<double>(k) / out.fps);
    while (seg + 2 < times.size() && times[seg + 1] <= t) ++seg;
    const double span = times[seg + 1] - times[seg];
    const double u = std::clamp((t - times[seg]) / span, 0.0, 1.0);
    const Pose& a = in.frames[seg];
    const Pose& b = in.frames[seg + 1];
    Pose p = a;
    p.root_pos = (1.0 - u) * a.root_pos + u * b.root_pos;
    for (std::size_t j = 0; j < p.rot.size(); ++j) p.rot[j] = canonical(a.rot[j].slerp(u, b.rot[j]).normalized());
    out.frames.push_back(std::move(p));
  }
  return out;
}

}  // namespace

Quat deepmimic_to_mimic() { return basis(); }

DeepMimicCharacter parse_deepmimic_character(std::string_view text, const std::string& source) {
  const YamlReader js(source, '"');
  const YAML::Node root = load_json_object(js, text);
  const YAML::Node joints = js.sequence(js.member(root, "Skeleton", "character"), "Joints", "\"Skeleton\"");
  if (joints.size() == 0) js.fail(joints, "\"Joints\" is empty");
  if (joints.size() > 4096) js.fail(joints, "more than 4096 joints");
  DeepMimicCharacter ch;
  Skeleton& sk = ch.skeleton;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const YAML::Node jn = joints[i];
    const std::string where = "joint " + std::to_string(i);
    const double id = js.number(jn, "ID", where);
    if (id != static_cast<double>(i)) js.fail(jn, where + ": \"ID\" is " + fmt_number(id) + ", joints must be listed in ID order (0, 1, 2, ...)");
    Joint j;
    j.name = js.text(jn, "Name", where);
    if (j.name.empty()) js.fail(jn, where + ": empty \"Name\"");
    if (sk.find(j.name) >= 0) js.fail(jn, where + ": duplicate joint name '" + j.name + "'");
    const std::string type = js.text(jn, "Type", where + " ('" + j.name + "')");
    const double parent = js.number(jn, "Parent", where);
    if (parent != std::floor(parent) || parent < -1 || parent >= static_cast<double>(i))
      js.fail(jn, where + " ('" + j.name + "'): \"Parent\" must be -1 for the root or an earlier joint's ID");
    j.parent = static_cast<int>(parent);
    if ((i == 0) != (j.parent == -1)) js.fail(jn, where + ": only the first joint may have \"Parent\" -1");
    const std::string jw = where + " ('" + j.name + "')";
    if (i == 0) {
      j.type = JointType::Free;  // DeepMimic ignores the root's attachment
    } else {
      j.offset = to_mimic(read_vec(js, jn, "Attach", jw));
      const Vec3 th = read_vec(js, jn, "AttachTheta", jw);
      j.rest = rot_to_mimic(deepmimic_euler(th.x(), th.y(), th.z()));
      if (type == "spherical") {
        j.type = JointType::Spherical;
        // DeepMimic limits are about its x, y, z; mimic's y is DeepMimic's -z, mimic's z its y.
        double lo[3], hi[3];
        for (int k = 0; k < 3; ++k) {
          lo[k] = js.number_or(jn, ("LimLow" + std::to_string(k)).c_str(), jw, -kPi);
          hi[k] = js.number_or(jn, ("LimHigh" + std::to_string(k)).c_str(), jw, kPi);
        }
        j.limits = {{lo[0], hi[0]}, {-hi[2], -lo[2]}, {lo[1], hi[1]}};
      } else if (type == "revolute") {
        j.type = JointType::Revolute;
        j.axis = to_mimic(Vec3::UnitZ());
        j.limits = {{js.number_or(jn, "LimLow0", jw, -kPi), js.number_or(jn, "LimHigh0", jw, kPi)}};
      } else if (type == "fixed") {
        j.type = JointType::Fixed;
      } else {
        js.fail(jn, jw + ": unsupported \"Type\" '" + type + "' (spherical, revolute, fixed)");
      }
      // DeepMimic writes LimLow > LimHigh (e.g. 1, 0) for "no limit".
      if (std::any_of(j.limits.begin(), j.limits.end(), [](const auto& lh) { return lh.first > lh.second; }))
        j.limits.clear();
    }
    j.torque_limit = js.number_or(jn, "TorqueLim", jw, 0.0);
    if (j.torque_limit < 0) js.fail(jn, jw + ": negative \"TorqueLim\"");
    j.end_effector = js.number_or(jn, "IsEndEffector", jw, 0.0) != 0.0;
    sk.joints.push_back(std::move(j));
  }

  if (const YAML::Node bodies = root["BodyDefs"]; bodies.IsDefined()) {
    if (!bodies.IsSequence()) js.fail(bodies, "\"BodyDefs\": expected an array");
    if (bodies.size() != joints.size())
      js.fail(bodies, "\"BodyDefs\" has " + std::to_string(bodies.size()) + " bodies for " +
                          std::to_string(joints.size()) + " joints");
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const YAML::Node bn = bodies[i];
      const std::string where = "body " + std::to_string(i);
      BodyDef b;
      b.name = js.text(bn, "Name", where);
      b.shape = js.text(bn, "Shape", where);
      b.mass = js.number(bn, "Mass", where);
      if (!(b.mass > 0)) js.fail(bn, where + " ('" + b.name + "'): \"Mass\" must be positive");
      b.pos = to_mimic(read_vec(js, bn, "Attach", where));
      const Vec3 th = read_vec(js, bn, "AttachTheta", where);
      b.rot = rot_to_mimic(deepmimic_euler(th.x(), th.y(), th.z()));
      const Vec3 p(js.number(bn, "Param0", where), js.number(bn, "Param1", where), js.number(bn, "Param2", where));
      if (p.minCoeff() < 0) js.fail(bn, where + ": negative size \"Param\"");
      if (b.shape == "box") b.size = Vec3(p.x(), p.z(), p.y());
      else if (b.shape == "capsule" || b.shape == "cylinder") b.size = Vec3(p.x(), p.x(), p.y());
      else if (b.shape == "sphere") b.size = Vec3::Constant(p.x());
      else js.fail(bn, where + ": unsupported \"Shape\" '" + b.shape + "' (box, capsule, cylinder, sphere)");
      const double group = js.number_or(bn, "ColGroup", where, 0);
      if (group != std::floor(group) || std::abs(group) > 1e9) js.fail(bn["ColGroup"], where + " \"ColGroup\": expected an integer");
      b.collision_group = static_cast<int>(group);
      b.fall_contact = js.number_or(bn, "EnableFallContact", where, 0) != 0;
      b.color = Eigen::Vector4d(js.number_or(bn, "ColorR", where, 0.5), js.number_or(bn, "ColorG", where, 0.5),
                                js.number_or(bn, "ColorB", where, 0.5), js.number_or(bn, "ColorA", where, 1.0));
      ch.bodies.push_back(std::move(b));
    }
  }
  try {
    sk.validate();
  } catch (const Error& e) {
    throw ParseError(source, 0, e.what());
  }
  return ch;
}

DeepMimicCharacter load_deepmimic_character(const std::filesystem::path& path) {
  return parse_deepmimic_character(read_text_file(path), path.string());
}

std::vector<PdGain> parse_deepmimic_pd_gains(std::string_view text, const std::string& source, const Skeleton& sk) {
  const YamlReader js(source, '"');
  const YAML::Node root = load_json_object(js, text);
  const YAML::Node ctrls = js.sequence(root, "PDControllers", "controller file");
  if (ctrls.size() != sk.joints.size())
    js.fail(ctrls, "\"PDControllers\" has " + std::to_string(ctrls.size()) + " entries for " +
                       std::to_string(sk.joints.size()) + " joints");
  std::vector<PdGain> gains(sk.joints.size());
  for (std::size_t i = 0; i < ctrls.size(); ++i) {
    const std::string where = "PD controller " + std::to_string(i);
    const std::string name = js.text(ctrls[i], "Name", where);
    if (name != sk.joints[i].name)
      js.fail(ctrls[i], where + ": named '" + name + "', the character's joint " + std::to_string(i) + " is '" + sk.joints[i].name + "'");
    gains[i].kp = js.number(ctrls[i], "Kp", where);
    gains[i].kd = js.number(ctrls[i], "Kd", where);
    if (gains[i].kp < 0 || gains[i].kd < 0) js.fail(ctrls[i], where + ": negative gain");
  }
  return gains;
}

Clip parse_deepmimic_motion(std::string_view text, const std::string& source, const Skeleton& sk) {
  const YamlReader js(source, '"');
  const YAML::Node root = load_json_object(js, text);
  Clip clip;
  clip.name = std::filesystem::path(source).stem().string();
  clip.skeleton = sk;
  if (const YAML::Node loop = root["Loop"]; loop.IsDefined()) {
    const std::string mode = loop.IsScalar() ? loop.Scalar() : "";
    if (mode == "wrap") clip.loop = LoopMode::Wrap;
    else if (mode == "none") clip.loop = LoopMode::None;
    else js.fail(loop, "\"Loop\" must be \"wrap\" or \"none\"");
  }
  std::size_t width = 1 + 7;
  for (std::size_t j = 1; j < sk.joints.size(); ++j) {
    if (sk.joints[j].type == JointType::Spherical) width += 4;
    else if (sk.joints[j].type == JointType::Revolute) width += 1;
  }
  const YAML::Node frames = js.sequence(root, "Frames", "motion");
  if (frames.size() == 0) js.fail(frames, "\"Frames\" is empty");
  std::vector<double> times;  // start time of each frame
  double min_dt = 0.0, last_dt = 0.0;
  std::vector<double> row(width);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const YAML::Node fr = frames[f];
    const std::string where = "frame " + std::to_string(f);
    if (!fr.IsSequence()) js.fail(fr, where + ": expected an array of numbers");
    if (fr.size() != width)
      js.fail(fr, where + ": has " + std::to_string(fr.size()) + " values, the character needs " +
                      std::to_string(width) + " (dt, root position 3, root rotation 4, then per joint)");
    for (std::size_t k = 0; k < width; ++k) row[k] = js.number(fr[k], where + " value " + std::to_string(k));
    // Each row's first value is its duration; the last row's is unused (often 0).
    const double dt = row[0];
    if (f + 1 < frames.size() || frames.size() == 1) {
      if (!(dt > 1e-6) || dt > 10.0) js.fail(fr, where + ": frame duration must be between 1e-6 and 10 s");
      min_dt = f == 0 ? dt : std::min(min_dt, dt);
    }
    times.push_back(f == 0 ? 0.0 : times.back() + last_dt);
    last_dt = dt;
    Pose p = rest_pose(sk);
    p.root_pos = to_mimic(Vec3(row[1], row[2], row[3]));
    if (!plausible_position(p.root_pos)) js.fail(fr, where + ": root position is beyond 1e4 m of the origin (a unit or file error)");
    std::size_t k = 4;
    auto read_quat = [&](const std::string& joint) {
      Quat q(row[k], row[k + 1], row[k + 2], row[k + 3]);
      k += 4;
      const double n = q.norm();
      // DeepMimic normalises on load, and its own clips rely on that (kick.txt has norms off by
      // 0.42): accept what DeepMimic accepts, refuse what cannot be a rotation.
      if (!(n > 0.5 && n < 1.5)) js.fail(fr, where + ": rotation of '" + printable_token(joint) + "' is not a unit quaternion (norm " + std::to_string(n) + ")");
      return rot_to_mimic(q.normalized());
    };
    p.rot[0] = read_quat(sk.joints[0].name);
    for (std::size_t j = 1; j < sk.joints.size(); ++j) {
      const Joint& jt = sk.joints[j];
      if (jt.type == JointType::Spherical) p.rot[j] = read_quat(jt.name);
      else if (jt.type == JointType::Revolute) p.rot[j] = canonical(Quat(Eigen::AngleAxisd(row[k++], jt.axis)));
    }
    clip.frames.push_back(std::move(p));
  }
  clip.fps = 1.0 / min_dt;
  if (times.size() > 1 && std::abs(times.back() - min_dt * static_cast<double>(times.size() - 1)) > 1e-6 * times.back())
  {
    try {
      clip = resample_irregular(clip, times, min_dt);
    } catch (const ParseError&) {
      throw;
    } catch (const Error& e) {
      throw ParseError(source, 0, e.what());
    }
  }
  return clip;
}

Clip load_deepmimic_motion(const std::filesystem::path& path, const Skeleton& sk) {
  return parse_deepmimic_motion(read_text_file(path), path.string(), sk);
}

std::string write_deepmimic_motion(const Clip& clip) {
  const Skeleton& sk = clip.skeleton;
  for (std::size_t j = 1; j < sk.joints.size(); ++j)
    if (sk.joints[j].type == JointType::Free) throw Error("clip '" + clip.name + "': a non-root free joint cannot be written");
  std::string out = "{\n\"Loop\": \"";
  out += to_string(clip.loop);
  out += "\",\n\"Frames\":\n[\n";
  char buf[64];
  auto put = [&](double v, bool first = false) {
    std::snprintf(buf, sizeof buf, "%s%.10g", first ? "" : ", ", v);
    out += buf;
  };
  for (std::size_t f = 0; f < clip.frames.size(); ++f) {
    const Pose& p = clip.frames[f];
    out += "[";
    put(1.0 / clip.fps, true);
    const Vec3 pos = basis().conjugate() * p.root_pos;
    for (int k = 0; k < 3; ++k) put(pos[k]);
    auto put_quat = [&](const Quat& q_m) {
      const Quat q = rot_to_deepmimic(q_m);
      put(q.w()), put(q.x()), put(q.y()), put(q.z());
    };
    put_quat(p.rot[0]);
    for (std::size_t j = 1; j < sk.joints.size(); ++j) {
      if (sk.joints[j].type == JointType::Spherical) put_quat(p.rot[j]);
      else if (sk.joints[j].type == JointType::Revolute) put(revolute_angle(sk.joints[j], p.rot[j]));
    }
    out += f + 1 < clip.frames.size() ? "],\n" : "]\n";
  }
  out += "]\n}\n";
  return out;
}

std::filesystem::path guess_deepmimic_character(const std::filesystem::path& motion_path) {
  const std::string stem = motion_path.stem().string();
  const auto cut = stem.find('_');
  if (cut == std::string::npos) return {};
  const std::filesystem::path dir = motion_path.parent_path();
  for (const auto& candidate : {dir.parent_path() / "characters" / (stem.substr(0, cut) + ".txt"),
                                dir / (stem.substr(0, cut) + ".txt")}) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
  }
  return {};
}

}  // namespace mimic
