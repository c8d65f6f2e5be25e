#include "motion/clip_io.hpp"


#include <cstdio>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/text_scanner.hpp"
#include "core/yaml_reader.hpp"
#include "motion/asf_amc.hpp"
#include "motion/bvh.hpp"
#include "motion/deepmimic.hpp"

namespace mimic {
namespace {

constexpr int kFormatVersion = 1;


void put(std::string& out, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  out += buf;
}

std::string vec_yaml(const double* v, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) {
    if (i) s += ", ";
    put(s, v[i]);
  }
  return s + "]";
}

// A YAML double-quoted string: control characters escaped so a name can never break a line
// (and so never end the header early).
std::string quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

}  // namespace

std::string write_clip(const Clip& clip) {
  clip.validate();
  std::string out = "# mimic clip: YAML header, a line '---', then one line per frame:\n"
                    "# root x y z, then w x y z for every joint (root first). See docs/clip-format.md\n";
  out += "format: mimic-clip\nversion: " + std::to_string(kFormatVersion) + "\n";
  out += "name: " + quote(clip.name) + "\nfps: ";
  put(out, clip.fps);
  out += "\nloop: " + std::string(to_string(clip.loop)) + "\nframes: " + std::to_string(clip.frames.size()) + "\njoints:\n";
  for (const Joint& j : clip.skeleton.joints) {
    out += "  - {name: " + quote(j.name) + ", parent: " + std::to_string(j.parent) + ", type: " + to_string(j.type);
    out += ", offset: " + vec_yaml(j.offset.data(), 3);
    const double rest[4] = {j.rest.w(), j.rest.x(), j.rest.y(), j.rest.z()};
    out += ", rest: " + vec_yaml(rest, 4);
    if (j.type == JointType::Revolute) out += ", axis: " + vec_yaml(j.axis.data(), 3);
    if (!j.limits.empty()) {
      out += ", limits: [";
      for (std::size_t k = 0; k < j.limits.size(); ++k) {
        const double lim[2] = {j.limits[k].first, j.limits[k].second};
        out += (k ? ", " : "") + vec_yaml(lim, 2);
      }
      out += "]";
    }
    if (j.torque_limit > 0) {
      out += ", torque_limit: ";
      put(out, j.torque_limit);
    }
    if (j.end_effector) out += ", end_effector: true";
    out += "}\n";
  }
  out += "sites:";
  out += clip.skeleton.sites.empty() ? " []\n" : "\n";
  for (const Site& s : clip.skeleton.sites)
    out += "  - {name: " + quote(s.name) + ", joint: " + std::to_string(s.joint) + ", offset: " + vec_yaml(s.offset.data(), 3) + "}\n";
  out += "---\n";
  for (const Pose& p : clip.frames) {
    for (int k = 0; k < 3; ++k) {
      if (k) out += ' ';
      put(out, p.root_pos[k]);
    }
    for (const Quat& q : p.rot) {
      for (double v : {q.w(), q.x(), q.y(), q.z()}) {
        out += ' ';
        put(out, v);
      }
    }
    out += '\n';
  }
  return out;
}

namespace {

}  // namespace

Clip parse_clip(std::string_view text, const std::string& source) {
  // Split at the first line that is exactly "---".
  std::size_t sep = std::string_view::npos;
  int header_lines = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t eol = text.find('\n', pos);
    if (eol == std::string_view::npos) eol = text.size();
    std::string_view line = text.substr(pos, eol - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    ++header_lines;
    if (line == "---") {
      sep = pos;
      break;
    }
    pos = eol + 1;
  }
  if (sep == std::string_view::npos) throw ParseError(source, 0, "not a mimic clip: no '---' line ends the header");
  const YamlReader hr(source);
  const YAML::Node h = hr.parse(text.substr(0, sep), "header is not valid YAML");
  if (!h.IsMap()) throw ParseError(source, 1, "header is not a YAML mapping");
  if (hr.text(hr.member(h, "format", "header"), "format") != "mimic-clip")
    hr.fail(h["format"], "'format' must be mimic-clip");
  const long version = hr.integer(hr.member(h, "version", "header"), "version");
  if (version != kFormatVersion)
    hr.fail(h["version"], "version " + std::to_string(version) + " is not supported (this build reads " + std::to_string(kFormatVersion) + ")");
  Clip clip;
  clip.name = h["name"].IsDefined() ? hr.text(h["name"], "name") : std::filesystem::path(source).stem().string();
  clip.fps = hr.number(hr.member(h, "fps", "header"), "fps");
  if (!(clip.fps > 0) || clip.fps > 1e6) hr.fail(h["fps"], "fps must be positive");
  const std::string loop = hr.text(hr.member(h, "loop", "header"), "loop");
  if (loop == "wrap") clip.loop = LoopMode::Wrap;
  else if (loop == "none") clip.loop = LoopMode::None;
  else hr.fail(h["loop"], "loop must be wrap or none");
  const long nframes = hr.integer(hr.member(h, "frames", "header"), "frames");
  if (nframes < 1 || nframes > 10'000'000) hr.fail(h["frames"], "frames must be between 1 and 10,000,000");

  const YAML::Node joints = hr.member(h, "joints", "header");
  if (!joints.IsSequence() || joints.size() == 0) hr.fail(joints, "joints: expected a non-empty list");
  if (joints.size() > 4096) hr.fail(joints, "more than 4096 joints");
  Skeleton& sk = clip.skeleton;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const YAML::Node jn = joints[i];
    const std::string where = "joint " + std::to_string(i);
    if (!jn.IsMap()) hr.fail(jn, where + ": expected a mapping");
    Joint j;
    j.name = hr.text(hr.member(jn, "name", where), where + " name");
    if (sk.find(j.name) >= 0) hr.fail(jn["name"], where + ": duplicate joint name '" + printable_token(j.name) + "'");
    const long parent = hr.integer(hr.member(jn, "parent", where), where + " parent");
    if (parent < -1 || parent >= static_cast<long>(i)) hr.fail(jn, where + ": parent must be -1 or an earlier joint");
    if ((i == 0) != (parent == -1)) hr.fail(jn, where + ": only joint 0, the root, has parent -1");
    j.parent = static_cast<int>(parent);
    if (!parse_joint_type(hr.text(hr.member(jn, "type", where), where + " type"), j.type))
      hr.fail(jn["type"], where + ": type must be free, spherical, revolute or fixed");
    if ((i == 0) != (j.type == JointType::Free))
      hr.fail(jn["type"], where + (i == 0 ? ": the root must be a free joint" : ": only the root (joint 0) may be a free joint"));
    if (jn["offset"].IsDefined()) j.offset = hr.vec<3>(jn["offset"], where + " offset");
    if (jn["rest"].IsDefined()) {
      const Eigen::Vector4d r = hr.vec<4>(jn["rest"], where + " rest");
      j.rest = Quat(r[0], r[1], r[2], r[3]);
      if (std::abs(j.rest.norm() - 1.0) > 1e-6) hr.fail(jn["rest"], where + ": rest is not a unit quaternion");
    }
    if (j.type == JointType::Revolute) {
      j.axis = hr.vec<3>(hr.member(jn, "axis", where), where + " axis");
      if (std::abs(j.axis.norm() - 1.0) > 1e-6) hr.fail(jn["axis"], where + ": axis is not a unit vector");
    }
    if (const YAML::Node lim = jn["limits"]; lim.IsDefined()) {
      if (!lim.IsSequence()) hr.fail(lim, where + ": limits must be a list of [low, high]");
      for (std::size_t k = 0; k < lim.size(); ++k) {
        const Eigen::Vector2d lh = hr.vec<2>(lim[k], where + " limits");
        if (lh[0] > lh[1]) hr.fail(lim[k], where + ": a lower limit exceeds its upper limit");
        j.limits.emplace_back(lh[0], lh[1]);
      }
    }
    if (jn["torque_limit"].IsDefined()) {
      j.torque_limit = hr.number(jn["torque_limit"], where + " torque_limit");
      if (j.torque_limit < 0) hr.fail(jn["torque_limit"], where + ": torque_limit is negative");
    }
    if (jn["end_effector"].IsDefined()) {
      const std::string ee = hr.text(jn["end_effector"], where + " end_effector");
      if (ee != "true" && ee != "false") hr.fail(jn["end_effector"], where + ": end_effector must be true or false");
      j.end_effector = ee == "true";
    }
    sk.joints.push_back(std::move(j));
  }
  if (const YAML::Node sites = h["sites"]; sites.IsDefined()) {
    if (!sites.IsSequence()) hr.fail(sites, "sites: expected a list");
    for (std::size_t i = 0; i < sites.size(); ++i) {
      const std::string where = "site " + std::to_string(i);
      if (!sites[i].IsMap()) hr.fail(sites[i], where + ": expected a mapping");
      Site s;
      s.name = hr.text(hr.member(sites[i], "name", where), where + " name");
      const long joint = hr.integer(hr.member(sites[i], "joint", where), where + " joint");
      if (joint < 0 || joint >= static_cast<long>(sk.joints.size())) hr.fail(sites[i], where + ": joint index out of range");
      s.joint = static_cast<int>(joint);
      s.offset = hr.vec<3>(hr.member(sites[i], "offset", where), where + " offset");
      sk.sites.push_back(std::move(s));
    }
  }
  try {
    sk.validate();
  } catch (const Error& e) {
    throw ParseError(source, 0, e.what());
  }

  if (nframes * static_cast<long>(sk.joints.size()) > kMaxClipRotations)
    hr.fail(h["frames"], "clip too large: " + std::to_string(nframes) + " frames of " + std::to_string(sk.joints.size()) +
                             " joints exceed " + std::to_string(kMaxClipRotations) + " joint rotations");

  // Frame rows, scanned with the header replaced by empty lines so that line numbers are the file's.
  const std::string rows = std::string(static_cast<std::size_t>(header_lines - 1), '\n') + std::string(text.substr(sep));
  TextScanner sc(rows, source);
  const int frames_line = h["frames"].Mark().line + 1;
  sc.expect_word("---");
  const std::size_t nj = sk.joints.size();
  const int width = 3 + 4 * static_cast<int>(nj);
  for (long f = 0; f < nframes; ++f) {
    if (sc.at_end()) sc.fail_at(frames_line, "file ends after " + std::to_string(f) + " frames, the header says " + std::to_string(nframes));
    const int line = sc.line();
    double v[4];
    Pose p;
    p.rot.resize(nj);
    auto value = [&](int idx) {
      if (sc.at_end() || sc.line() != line)
        sc.fail_at(line, "frame " + std::to_string(f) + " has " + std::to_string(idx) + " values, expected " + std::to_string(width));
      return sc.expect_double("a frame value");
    };
    int idx = 0;
    for (int k = 0; k < 3; ++k) p.root_pos[k] = value(idx++);
    if (!plausible_position(p.root_pos))
      sc.fail_at(line, "frame " + std::to_string(f) + ": root position is beyond 1e4 m of the origin (a unit or file error)");
    for (std::size_t j = 0; j < nj; ++j) {
      for (double& x : v) x = value(idx++);
      Quat q(v[0], v[1], v[2], v[3]);
      if (std::abs(q.norm() - 1.0) > 1e-3)
        sc.fail_at(line, "frame " + std::to_string(f) + ": rotation of joint '" + sk.joints[j].name + "' is not a unit quaternion");
      p.rot[j] = q.normalized();
    }
    if (!sc.at_end() && sc.line() == line)
      sc.fail_at(line, "frame " + std::to_string(f) + " has more than " + std::to_string(width) + " values");
    clip.frames.push_back(std::move(p));
  }
  if (!sc.at_end()) sc.fail("more frame rows than the header's frames: " + std::to_string(nframes));
  return clip;
}

void save_clip(const Clip& clip, const std::filesystem::path& path) { write_file_atomic(path, write_clip(clip)); }

Clip load_motion(const std::filesystem::path& path, const LoadOptions& opts) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".mclip") return parse_clip(read_text_file(path), path.string());
  if (ext == ".bvh") return load_bvh(path, opts.axes);
  if (ext == ".amc") {
    std::filesystem::path asf = opts.asf.empty() ? guess_asf(path) : opts.asf;
    if (asf.empty()) throw Error(path.string() + ": an AMC motion needs its ASF skeleton (--asf FILE)");
    return load_amc(path, load_asf(asf), opts.amc_fps);
  }
  if (ext == ".txt" || ext == ".json") {
    std::filesystem::path ch = opts.character.empty() ? guess_deepmimic_character(path) : opts.character;
    if (ch.empty()) throw Error(path.string() + ": a DeepMimic motion needs its character file (--character FILE)");
    return load_deepmimic_motion(path, load_deepmimic_character(ch).skeleton);
  }
  throw Error(path.string() + ": unknown motion format '" + ext + "' (expected .mclip, .bvh, .amc or DeepMimic .txt)");
}

}  // namespace mimic
