#include "motion/retarget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/text_scanner.hpp"
#include "core/yaml_reader.hpp"
#include "motion/effector_ik.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

namespace {

// A node yaml-cpp can answer about: a missing key of a const mapping is an invalid node, whose
// type queries throw.
bool has(const YAML::Node& n) { return n.IsDefined(); }
bool scalar(const YAML::Node& n) { return n.IsDefined() && n.IsScalar(); }

RetargetMap parse_map(std::string_view text, const std::string& source) {
  RetargetMap map;
  map.source = source;
  const YamlReader yr(source);
  const YAML::Node root = yr.parse(text, "not valid YAML");
  auto fail = [&](const YAML::Node& n, const std::string& msg) { yr.fail(n, msg); };
  if (!root.IsMap()) fail(root, "expected a mapping with 'joints'");
  for (const auto& kv : root) {
    if (!kv.first.IsScalar()) fail(kv.first, "a key must be a name");
    const std::string key = kv.first.Scalar();
    if (key != "joints" && key != "scale" && key != "sites" && key != "end_effectors" && key != "ground_fix" && key != "ik" && key != "contacts")
      fail(kv.first, "unknown key '" + key + "' (joints, scale, sites, end_effectors, ik, contacts, ground_fix)");
  }
  const YAML::Node joints = root["joints"];
  if (!has(joints) || !joints.IsMap() || joints.size() == 0) fail(has(joints) ? joints : root, "'joints' must map target joint names to source joint names");
  for (const auto& kv : joints) {
    if (!kv.first.IsScalar()) fail(kv.first, "joints: a target joint must be a name");
    std::vector<std::string> sources;
    if (kv.second.IsScalar()) sources.push_back(kv.second.Scalar());
    if (kv.second.IsSequence())
      for (const YAML::Node& n : kv.second)
        if (n.IsScalar()) sources.push_back(n.Scalar());
    if (sources.empty() || (kv.second.IsSequence() && sources.size() != kv.second.size()))
      fail(kv.second, "joints: the source of '" + kv.first.Scalar() + "' must be a joint name or a list of them (the first the clip has)");
    map.joints.emplace_back(kv.first.Scalar(), std::move(sources));
  }
  if (const YAML::Node s = root["scale"]; s.IsDefined()) {
    if (s.IsScalar() && s.Scalar() == "auto") {
      map.scale = 0.0;
    } else if (!s.IsScalar() || !parse_double(s.Scalar(), map.scale) || !(map.scale > 0) || map.scale > 1000) {
      fail(s, "'scale' must be a positive number (at most 1000) or auto");
    }
  }
  if (const YAML::Node sites = root["sites"]; sites.IsDefined()) {
    if (!sites.IsSequence()) fail(sites, "'sites' must be a list");
    for (const YAML::Node& s : sites) {
      RetargetSite site;
      if (!s.IsMap() || !scalar(s["name"]) || !scalar(s["joint"]) || !has(s["offset"]) || !s["offset"].IsSequence() || s["offset"].size() != 3)
        fail(s, "a site needs name, joint and offset: [x, y, z]");
      site.name = s["name"].Scalar();
      site.joint = s["joint"].Scalar();
      for (std::size_t k = 0; k < 3; ++k)
        if (!scalar(s["offset"][k]) || !parse_double(s["offset"][k].Scalar(), site.offset[static_cast<Eigen::Index>(k)]))
          fail(s["offset"], "site offset must be 3 numbers");
      map.sites.push_back(site);
    }
  }
  const auto names = [&](const char* key, std::vector<std::string>& out) {
    const YAML::Node e = root[key];
    if (!e.IsDefined()) return;
    if (!e.IsSequence()) fail(e, std::string("'") + key + "' must be a list of names");
    for (const YAML::Node& n : e) {
      if (!n.IsScalar()) fail(n, std::string("'") + key + "' must be a list of names");
      out.push_back(n.Scalar());
    }
  };
  names("end_effectors", map.end_effectors);
  names("ik", map.ik);
  names("contacts", map.contacts);
  for (std::size_t i = 0; i < map.contacts.size(); ++i)
    if (std::find(map.ik.begin(), map.ik.end(), map.contacts[i]) == map.ik.end())
      fail(root["contacts"][i], "contact '" + map.contacts[i] + "' is not one of the 'ik' joints (a contact is held by inverse kinematics)");
  if (const YAML::Node g = root["ground_fix"]; g.IsDefined()) {
    if (!g.IsScalar() || (g.Scalar() != "true" && g.Scalar() != "false")) fail(g, "'ground_fix' must be true or false");
    map.ground_fix = g.Scalar() == "true";
  }
  return map;
}

}  // namespace

RetargetMap parse_retarget_map(std::string_view text, const std::string& source) {
  try {
    return parse_map(text, source);
  } catch (const YAML::Exception& e) {  // what the checks above did not foresee: still named
    throw ParseError(source, e.mark.line + 1, "not a retarget map (" + e.msg + ")");
  }
}

RetargetMap load_retarget_map(const std::filesystem::path& path) {
  return parse_retarget_map(read_text_file(path), path.string());
}

int find_source_joint(const Skeleton& source, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    if (const int i = source.find(name); i >= 0) return i;
    int found = -1, count = 0;
    for (int j = 0; j < source.num_joints(); ++j) {
      const std::string& full = source.joints[static_cast<std::size_t>(j)].name;
      const std::size_t colon = full.rfind(':');
      if (colon != std::string::npos && std::string_view(full).substr(colon + 1) == name) found = j, ++count;
    }
    if (count == 1) return found;
  }
  return -1;
}

bool map_fits(const RetargetMap& map, const Skeleton& source, const Skeleton& target) {
  for (const auto& [t, s] : map.joints)
    if (target.find(t) < 0 || find_source_joint(source, s) < 0) return false;
  for (const RetargetSite& site : map.sites)
    if (target.find(site.joint) < 0) return false;
  return true;
}

namespace {

// Below this (rest_uprightness), the source was read with the wrong up axis. Measured on the CMU
// walk onto humanoid3d: 0.92 read right, 0.04 or less lying (up x, z or -z), -0.92 upside down;
// the walk onto humanoid3d made longer-legged: 0.99.
constexpr double kMinUprightness = 0.5;

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : " or '") + n + "'";
  return out;
}

// The turn about the vertical, in quarter turns (0-3), that best takes the target's rest pose onto
// the source's: the mapped joints' horizontal offsets from the root, matched in 2-D (Kabsch), the
// angle rounded to the nearest quarter turn. A source imported with the right axes gives 0.
int rest_quarter_turns(const LinkFrames& src_rest, const LinkFrames& tgt_rest, const std::vector<int>& source_of) {
  double dot = 0.0, cross = 0.0;
  const Vec3 t0 = tgt_rest.joint_pos[0], s0 = src_rest.joint_pos[static_cast<std::size_t>(source_of[0])];
  for (std::size_t t = 1; t < source_of.size(); ++t) {
    if (source_of[t] < 0) continue;
    const Vec3 a = tgt_rest.joint_pos[t] - t0, b = src_rest.joint_pos[static_cast<std::size_t>(source_of[t])] - s0;
    dot += a.x() * b.x() + a.y() * b.y();
    cross += a.x() * b.y() - a.y() * b.x();
  }
  if (std::abs(dot) + std::abs(cross) < 1e-12) return 0;
  const double quarters = std::round(std::atan2(cross, dot) / (M_PI / 2));
  return (static_cast<int>(quarters) % 4 + 4) % 4;
}

// How far the source stands up at rest as the target does, over the mapped joints' offsets from
// the root: the sum of the products of source and target heights over the product of the
// offsets' whole lengths, relative to the same for the target with itself (1 for a source alike
// the target, 0 where it lies, -1 on its head; a four-legged target's own horizontal spine does
// not lower it). 1 where nothing but the root is mapped.
double rest_uprightness(const LinkFrames& src_rest, const LinkFrames& tgt_rest, const std::vector<int>& source_of) {
  double heights = 0, target_heights = 0, target_sq = 0, source_sq = 0;
  for (std::size_t t = 1; t < source_of.size(); ++t) {
    if (source_of[t] < 0) continue;
    const Vec3 a = tgt_rest.joint_pos[t] - tgt_rest.joint_pos[0];
    const Vec3 b = src_rest.joint_pos[static_cast<std::size_t>(source_of[t])] - src_rest.joint_pos[static_cast<std::size_t>(source_of[0])];
    heights += a.z() * b.z(), target_heights += a.z() * a.z(), target_sq += a.squaredNorm(), source_sq += b.squaredNorm();
  }
  if (target_heights < 1e-12 || source_sq < 1e-12) return 1.0;
  return heights / std::sqrt(target_sq * source_sq) / (target_heights / target_sq);
}

// The target's rest frames turned about the vertical by quarter turns: where a source faces
// another way at rest, its rotations relative to its rest are carried onto the target turned so.
void turn_about_vertical(LinkFrames& rest, int quarter_turns) {
  const Quat q(Eigen::AngleAxisd(quarter_turns * M_PI / 2, Vec3::UnitZ()));
  for (Vec3& p : rest.joint_pos) p = q * p;
  for (Quat& r : rest.joint_rot) r = q * r;
}

// Direction of the "bone" that leaves joint j in the rest pose: towards the mapped child (or the
// first child / first site) of the target; zero if there is none.
Vec3 bone_direction(const Skeleton& sk, const LinkFrames& rest, int j, const std::vector<int>& preferred_child) {
  int child = preferred_child[static_cast<std::size_t>(j)];
  if (child < 0) {
    for (int c = j + 1; c < sk.num_joints(); ++c)
      if (sk.joints[static_cast<std::size_t>(c)].parent == j) { child = c; break; }
  }
  if (child >= 0) return rest.joint_pos[static_cast<std::size_t>(child)] - rest.joint_pos[static_cast<std::size_t>(j)];
  return Vec3::Zero();
}

}  // namespace

Clip retarget(const Clip& src, const Skeleton& target_in, const RetargetMap& map, RetargetReport* report) {
  src.validate();
  Skeleton target = target_in;
  auto need = [&](const Skeleton& sk, const std::string& name, const char* side) {
    const int i = sk.find(name);
    if (i < 0) throw Error(map.source + ": " + side + " joint '" + name + "' does not exist in the " + side + " skeleton");
    return i;
  };
  for (const RetargetSite& s : map.sites) target.sites.push_back(Site{s.name, need(target, s.joint, "target"), s.offset});
  target.validate();
  const int nt = target.num_joints();
  std::vector<int> source_of(static_cast<std::size_t>(nt), -1);
  for (const auto& [t, s] : map.joints) {
    const int sj = find_source_joint(src.skeleton, s);
    if (sj < 0) throw Error(map.source + ": source joint " + joined(s) + " does not exist in the source skeleton");
    source_of[static_cast<std::size_t>(need(target, t, "target"))] = sj;
  }
  if (source_of[0] < 0) throw Error(map.source + ": the target root '" + target.joints[0].name + "' must be mapped");

  // Rest poses, the target's turned to face where the source's faces, and the bone-by-bone
  // alignment of the target's rest onto the source's.
  const LinkFrames src_rest = forward_kinematics(src.skeleton, rest_pose(src.skeleton));
  LinkFrames tgt_rest = forward_kinematics(target, rest_pose(target));
  if (const double upright = rest_uprightness(src_rest, tgt_rest, source_of); upright < kMinUprightness) {
    char value[32];
    std::snprintf(value, sizeof value, "%.2f", upright);
    throw Error(map.source + ": the source does not stand up at rest along the up axis it was read with (its mapped joints' heights " +
                "agree with the target's by " + value + ", where 1 is alike and 0 lying); read it with the right --up (y for most BVH files)");
  }
  const int turns = rest_quarter_turns(src_rest, tgt_rest, source_of);
  if (turns != 0) turn_about_vertical(tgt_rest, turns);
  std::vector<int> mapped_child(static_cast<std::size_t>(nt), -1);
  for (int c = nt - 1; c > 0; --c)
    if (source_of[static_cast<std::size_t>(c)] >= 0) mapped_child[static_cast<std::size_t>(target.joints[static_cast<std::size_t>(c)].parent)] = c;

  double scale = map.scale;
  if (scale <= 0.0) {
    double tlo = std::numeric_limits<double>::infinity(), thi = -tlo, slo = tlo, shi = -tlo;
    for (int t = 0; t < nt; ++t) {
      const int s = source_of[static_cast<std::size_t>(t)];
      if (s < 0) continue;
      tlo = std::min(tlo, tgt_rest.joint_pos[static_cast<std::size_t>(t)].z());
      thi = std::max(thi, tgt_rest.joint_pos[static_cast<std::size_t>(t)].z());
      slo = std::min(slo, src_rest.joint_pos[static_cast<std::size_t>(s)].z());
      shi = std::max(shi, src_rest.joint_pos[static_cast<std::size_t>(s)].z());
    }
    if (!(shi - slo > 1e-9) || !(thi - tlo > 1e-9)) throw Error(map.source + ": cannot infer the scale (mapped joints have no height); give 'scale'");
    scale = (thi - tlo) / (shi - slo);
  }

  // align[t]: global rotation applied to the target's rest frame so its bone points like the
  // source's rest bone. delta = source rotation relative to its rest, transferred globally.
  std::vector<Quat> align(static_cast<std::size_t>(nt), Quat::Identity());
  for (int t = 0; t < nt; ++t) {
    const int s = source_of[static_cast<std::size_t>(t)];
    const int tc = mapped_child[static_cast<std::size_t>(t)];
    if (s < 0 || tc < 0) continue;
    const Vec3 dt = bone_direction(target, tgt_rest, t, mapped_child);
    const Vec3 ds = src_rest.joint_pos[static_cast<std::size_t>(source_of[static_cast<std::size_t>(tc)])] -
                    src_rest.joint_pos[static_cast<std::size_t>(s)];
    if (dt.norm() > 1e-9 && ds.norm() > 1e-9) align[static_cast<std::size_t>(t)] = Quat::FromTwoVectors(dt, ds);
  }

  Clip out;
  out.name = src.name;
  out.fps = src.fps;
  out.loop = src.loop;
  out.skeleton = target;
  out.frames.reserve(src.frames.size());
  LinkFrames sfk;
  std::vector<Quat> tglob(static_cast<std::size_t>(nt));
  for (const Pose& sp : src.frames) {
    forward_kinematics(src.skeleton, sp, sfk);
    Pose tp = rest_pose(target);
    tp.root_pos = scale * sfk.joint_pos[static_cast<std::size_t>(source_of[0])];
    for (int t = 0; t < nt; ++t) {
      const auto tu = static_cast<std::size_t>(t);
      const Joint& jt = target.joints[tu];
      const Quat parent_frame = t == 0 ? Quat::Identity() : tglob[static_cast<std::size_t>(jt.parent)] * jt.rest;
      const int s = source_of[tu];
      if (s < 0 || jt.type == JointType::Fixed) {
        tglob[tu] = parent_frame * tp.rot[tu];
        continue;
      }
      const auto su = static_cast<std::size_t>(s);
      const Quat desired = sfk.joint_rot[su] * src_rest.joint_rot[su].conjugate() * align[tu] * tgt_rest.joint_rot[tu];
      Quat local = (parent_frame.conjugate() * desired).normalized();
      if (jt.type == JointType::Revolute) local = Quat(Eigen::AngleAxisd(twist_angle(local, jt.axis), jt.axis));
      tp.rot[tu] = canonical(local);
      tglob[tu] = parent_frame * tp.rot[tu];
    }
    out.frames.push_back(std::move(tp));
  }

  // The source's joints in the world, scaled (where the target's should be, before the shift).
  std::vector<std::vector<Vec3>> scaled(src.frames.size());
  for (std::size_t f = 0; f < src.frames.size(); ++f) {
    forward_kinematics(src.skeleton, src.frames[f], sfk);
    for (const Vec3& p : sfk.joint_pos) scaled[f].push_back(scale * p);
  }
  const auto mapped = [&](const std::string& name, const char* what) {
    const int tj = target.find(name);
    if (tj < 0) throw Error(map.source + ": " + what + " '" + name + "' is not a target joint");
    const int sj = source_of[static_cast<std::size_t>(tj)];
    if (sj < 0) throw Error(map.source + ": " + what + " '" + name + "' is not mapped to a source joint");
    return std::pair<int, int>{tj, sj};
  };
  const auto source_track = [&](int sj) {
    std::vector<Vec3> track;
    for (const auto& frame : scaled) track.push_back(frame[static_cast<std::size_t>(sj)]);
    return track;
  };
  const auto target_track = [&](const std::vector<Pose>& frames, int tj) {
    std::vector<Vec3> track;
    LinkFrames tfk;
    for (const Pose& p : frames) {
      forward_kinematics(target, p, tfk);
      track.push_back(tfk.joint_pos[static_cast<std::size_t>(tj)]);
    }
    return track;
  };

  // Inverse kinematics: the ik joints to the scaled source's positions, the contacts held still
  // on the ground through the source's stance (motion/effector_ik.hpp).
  const std::vector<Pose> transferred = out.frames;
  std::vector<EffectorGoal> goals;
  std::vector<std::pair<int, std::vector<bool>>> stances;  // contact joint, its stance frames
  for (const std::string& name : map.ik) {
    const auto [tj, sj] = mapped(name, "ik joint");
    EffectorGoal goal{tj, source_track(sj)};
    if (std::find(map.contacts.begin(), map.contacts.end(), name) != map.contacts.end()) {
      stances.emplace_back(tj, stance_frames(goal.position, src.fps));
      hold_stance(goal.position, stances.back().second);
    }
    goals.push_back(std::move(goal));
  }
  if (!goals.empty()) reach_effectors(target, out.frames, goals);

  double shift = 0.0;
  if (map.ground_fix) {
    shift = -clip_min_height(out);
    for (Pose& p : out.frames) p.root_pos.z() += shift;
  }

  if (report) {
    report->scale = scale;
    report->ground_shift = shift;
    report->source_turn = turns == 3 ? -90 : 90 * turns;
    report->effectors.clear();
    const Vec3 up(0, 0, shift);
    const std::vector<Vec3> root = target_track(out.frames, 0);
    for (const std::string& name : map.end_effectors) {
      const auto [tj, sj] = mapped(name, "end effector");
      const std::vector<Vec3> want = source_track(sj), got = target_track(out.frames, tj), before = target_track(transferred, tj);
      EffectorError e{name, 0.0, 0.0, 0.0, 0.0};
      for (std::size_t f = 0; f < want.size(); ++f) {
        const double err = ((want[f] - scaled[f][static_cast<std::size_t>(source_of[0])]) - (got[f] - root[f])).norm();
        e.mean += err, e.max = std::max(e.max, err);
        e.world_mean += (got[f] - up - want[f]).norm();
        e.world_mean_before_ik += (before[f] - want[f]).norm();
      }
      const auto n = static_cast<double>(std::max<std::size_t>(1, want.size()));
      e.mean /= n, e.world_mean /= n, e.world_mean_before_ik /= n;
      report->effectors.push_back(e);
    }
    report->contacts.clear();
    for (const auto& [tj, stance] : stances)
      report->contacts.push_back(ContactReport{target.joints[static_cast<std::size_t>(tj)].name,
                                               static_cast<int>(std::count(stance.begin(), stance.end(), true)),
                                               stance_sliding(target_track(out.frames, tj), stance, src.fps),
                                               stance_sliding(target_track(transferred, tj), stance, src.fps)});
    report->frames_below_floor = 0;
    LinkFrames tfk;
    for (const Pose& p : out.frames) {
      forward_kinematics(target, p, tfk);
      double lowest = std::numeric_limits<double>::infinity();
      for (const auto* points : {&tfk.joint_pos, &tfk.site_pos})
        for (const Vec3& x : *points) lowest = std::min(lowest, x.z());
      report->frames_below_floor += lowest < -1e-9;
    }
  }
  // A scale or a site far out of proportion gives positions no capture has (found by the fuzzer).
  try {
    out.validate();
  } catch (const Error& e) {
    throw Error(map.source + ": the retargeted clip is not a valid motion (" + std::string(e.what()) + "); check 'scale' and the sites");
  }
  return out;
}

}  // namespace mimic
