#include "sim/character_model.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "motion/kinematics.hpp"

namespace mimic {

CharacterModel CharacterModel::from_deepmimic(const std::filesystem::path& character, const std::filesystem::path& controller) {
  DeepMimicCharacter dm = load_deepmimic_character(character);
  CharacterModel ch;
  ch.name = character.stem().string();
  ch.skeleton = std::move(dm.skeleton);
  ch.bodies = std::move(dm.bodies);
  if (ch.bodies.empty()) throw Error(character.string() + ": the character has no \"BodyDefs\"; it cannot be simulated");
  if (!controller.empty()) {
    ch.gains = parse_deepmimic_pd_gains(read_text_file(controller), controller.string(), ch.skeleton);
  } else {
    // Without a controller file: gains scaled to each joint's torque limit.
    ch.gains.resize(ch.skeleton.joints.size());
    for (std::size_t j = 1; j < ch.gains.size(); ++j) {
      const double t = ch.skeleton.joints[j].torque_limit > 0 ? ch.skeleton.joints[j].torque_limit : 100.0;
      ch.gains[j] = PdGain{2.5 * t, 0.25 * t};
    }
  }
  ch.validate();
  return ch;
}

namespace {

// Body part of a joint, from its name (CMU/ASF, BVH and DeepMimic naming): sets the capsule
// radius, the share of the body mass and the servo's strength (seed 000: strong legs, weak toes).
struct BodyPart {
  const char* keywords[6];
  double radius;      // m
  double kp;          // N m / rad for a 70 kg body
  double torque;      // N m
};
constexpr BodyPart kParts[] = {
    {{"toe"}, 0.025, 40, 20},
    {{"finger", "thumb", "hand", "wrist"}, 0.03, 30, 20},
    {{"foot", "ankle"}, 0.04, 300, 90},
    {{"tibia", "knee", "shin", "leg"}, 0.05, 500, 150},
    {{"femur", "thigh", "hip", "upleg"}, 0.065, 500, 200},
    {{"radius", "elbow", "forearm"}, 0.035, 200, 60},
    {{"humerus", "shoulder", "arm", "clavicle", "collar"}, 0.045, 300, 100},
    {{"head", "neck"}, 0.06, 150, 50},
};
constexpr BodyPart kTorso{{"torso"}, 0.09, 800, 200};  // spine, chest, back, pelvis, root ...

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

const BodyPart& body_part(const std::string& joint_name) {
  const std::string n = lower(joint_name);
  for (const BodyPart& p : kParts)
    for (const char* k : p.keywords)
      if (k && n.find(k) != std::string::npos) return p;
  return kTorso;
}

}  // namespace

CharacterModel CharacterModel::from_skeleton(const Skeleton& sk, const std::string& name, double total_mass) {
  sk.validate();
  if (!(total_mass > 0)) throw Error("character '" + name + "': total mass must be positive");
  CharacterModel ch;
  ch.name = name;
  ch.skeleton = sk;
  const auto children = sk.children();
  double volume = 0.0;
  std::vector<double> volumes;
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    // The bone: towards the child nearest the body's mid-plane (the spine continues to the
    // neck, not to a shoulder), the farthest of those; else the joint's first site; none: a sphere.
    Vec3 tip = Vec3::Zero();
    double best_side = std::numeric_limits<double>::infinity();
    for (int c : children[j]) {
      const Vec3& o = sk.joints[static_cast<std::size_t>(c)].offset;
      if (o.norm() < 0.01) continue;
      const double side = std::round(std::abs(o.y()) * 100.0);  // centimetres off the mid-plane
      if (side < best_side || (side == best_side && o.norm() > tip.norm())) tip = o, best_side = side;
    }
    if (tip.norm() < 0.01)
      for (const Site& site : sk.sites)
        if (site.joint == static_cast<int>(j)) { tip = site.offset; break; }
    const BodyPart& part = j == 0 ? kTorso : body_part(sk.joints[j].name);
    const double r = part.radius;
    BodyDef b;
    b.name = sk.joints[j].name;
    b.color = Eigen::Vector4d(0.47, 0.55, 0.69, 1.0);
    const bool leaf_foot = children[j].empty() && &part == &kParts[2] && tip.norm() >= 0.01;
    if (leaf_foot) {
      // A foot with no toe joint: a sole box under the bone's tip (seed 000's and DeepMimic's
      // humanoids stand on boxes; a capsule's rounded end is a point contact nothing balances on).
      // From 1.25 radii behind the joint to 2.75 radii ahead of the tip along +x (mimic's
      // forward), 2.25 radii wide, 1.25 radii thick, its bottom at the tip's height.
      const double heel = -1.25 * r, toe = tip.x() + 2.75 * r, thick = 1.25 * r;
      b.shape = "box";
      b.pos = Vec3((heel + toe) / 2, tip.y(), tip.z() + thick / 2);
      b.size = Vec3(toe - heel, 2.25 * r, thick);
      volumes.push_back(b.size.x() * b.size.y() * b.size.z());
    } else if (tip.norm() < 0.01) {
      b.shape = "sphere";
      b.size = Vec3::Constant(2 * r);
      volumes.push_back(4.0 / 3.0 * kPi * r * r * r);
    } else {
      // Capsule between the joint and the bone's tip, shortened by the radius at both ends so
      // neighbouring capsules meet rather than overlap.
      const double length = std::max(tip.norm() - 2 * r, 0.01);
      b.shape = "capsule";
      b.pos = tip / 2;
      b.rot = Quat::FromTwoVectors(Vec3::UnitZ(), tip);
      b.size = Vec3(2 * r, 2 * r, length);
      volumes.push_back(kPi * r * r * length + 4.0 / 3.0 * kPi * r * r * r);
    }
    volume += volumes.back();
    ch.bodies.push_back(b);
  }
  // Masses in proportion to volume, summing to the requested body mass; gains scale with it.
  const double scale = total_mass / 70.0;
  ch.gains.resize(sk.joints.size());
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    ch.bodies[j].mass = std::max(1e-3 * total_mass, total_mass * volumes[j] / volume);
    if (j == 0) continue;
    const BodyPart& part = body_part(sk.joints[j].name);
    ch.gains[j] = PdGain{part.kp * scale, 0.1 * part.kp * scale};
    if (ch.skeleton.joints[j].torque_limit <= 0) ch.skeleton.joints[j].torque_limit = part.torque * scale;
  }
  return ch;
}

double CharacterModel::total_mass() const {
  double m = 0;
  for (const BodyDef& b : bodies) m += b.mass;
  return m;
}

void CharacterModel::validate() const {
  skeleton.validate();
  if (bodies.size() != skeleton.joints.size())
    throw Error("character '" + name + "': " + std::to_string(bodies.size()) + " bodies for " + std::to_string(skeleton.joints.size()) + " joints");
  if (gains.size() != skeleton.joints.size()) throw Error("character '" + name + "': one PD gain per joint is needed");
  for (const BodyDef& b : bodies)
    if (!(b.mass > 0) || !b.size.allFinite() || b.size.minCoeff() <= 0) throw Error("character '" + name + "': body '" + b.name + "' needs a positive mass and size");
}

namespace {

// Lowest and highest z of a body's shape given its world frame.
std::pair<double, double> shape_z_extent(const BodyDef& b, const Vec3& pos, const Quat& rot) {
  const Mat3 r = rot.toRotationMatrix();
  if (b.shape == "sphere") return {pos.z() - b.size.x() / 2, pos.z() + b.size.x() / 2};
  if (b.shape == "box") {
    const double h = 0.5 * (std::abs(r(2, 0)) * b.size.x() + std::abs(r(2, 1)) * b.size.y() + std::abs(r(2, 2)) * b.size.z());
    return {pos.z() - h, pos.z() + h};
  }
  // capsule / cylinder along the body's z: segment of length size.z, radius size.x / 2
  const double half = 0.5 * b.size.z() * std::abs(r(2, 2));
  const double rad = b.size.x() / 2;
  return {pos.z() - half - rad, pos.z() + half + rad};
}

std::string num(double v) { return fmt::format("{:.9g}", v); }
std::string vec(const Vec3& v) { return num(v.x()) + " " + num(v.y()) + " " + num(v.z()); }
std::string quat(const Quat& q) { return num(q.w()) + " " + num(q.x()) + " " + num(q.y()) + " " + num(q.z()); }

std::string geom_xml(const BodyDef& b) {
  std::string size;
  std::string type = b.shape;
  if (b.shape == "sphere") size = num(b.size.x() / 2);
  else if (b.shape == "box") size = vec(b.size / 2);
  else size = num(b.size.x() / 2) + " " + num(b.size.z() / 2);  // capsule, cylinder
  return fmt::format("<geom name=\"{}\" type=\"{}\" size=\"{}\" pos=\"{}\" quat=\"{}\" mass=\"{}\" rgba=\"{} {} {} {}\"/>",
                     b.name, type, size, vec(b.pos), quat(b.rot), num(b.mass), num(b.color[0]), num(b.color[1]), num(b.color[2]), num(b.color[3]));
}

}  // namespace

namespace {
// Lowest and highest body point in the rest pose with the root at the origin.
std::pair<double, double> rest_extent(const CharacterModel& ch) {
  const LinkFrames fk = forward_kinematics(ch.skeleton, rest_pose(ch.skeleton));
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t j = 0; j < ch.bodies.size(); ++j) {
    const BodyDef& b = ch.bodies[j];
    const auto [a, c] = shape_z_extent(b, fk.joint_pos[j] + fk.joint_rot[j] * b.pos, fk.joint_rot[j] * b.rot);
    lo = std::min(lo, a);
    hi = std::max(hi, c);
  }
  return {lo, hi};
}
}  // namespace

double CharacterModel::rest_height() const {
  const auto [lo, hi] = rest_extent(*this);
  return hi - lo;
}

double CharacterModel::rest_root_height() const { return -rest_extent(*this).first; }

std::string build_mjcf(const CharacterModel& ch, const MjcfOptions& opts) {
  ch.validate();
  const Skeleton& sk = ch.skeleton;
  std::string xml = fmt::format(
      "<mujoco model=\"{}\">\n"
      "  <!-- generated by mimic from the character '{}' -->\n"
      "  <compiler angle=\"radian\" inertiafromgeom=\"true\"/>\n"
      "  <option timestep=\"{}\" gravity=\"0 0 -9.81\" integrator=\"Euler\"/>\n"
      "  <size njmax=\"{}\" nconmax=\"{}\"/>\n"
      "  <visual><global offwidth=\"1280\" offheight=\"720\"/><quality shadowsize=\"2048\"/></visual>\n"
      "{}"
      "  <default>\n"
      "    <joint armature=\"{}\" limited=\"false\"/>\n"
      "    <geom contype=\"2\" conaffinity=\"1\" condim=\"3\" friction=\"{} 0.005 0.0001\"/>\n"
      "  </default>\n"
      "  <asset>\n"
      "    <texture name=\"grid\" type=\"2d\" builtin=\"checker\" rgb1=\".82 .84 .86\" rgb2=\".72 .74 .76\" width=\"512\" height=\"512\"/>\n"
      "    <material name=\"grid\" texture=\"grid\" texrepeat=\"1 1\" texuniform=\"true\" reflectance=\".05\"/>\n"
      "    <texture name=\"sky\" type=\"skybox\" builtin=\"gradient\" rgb1=\".55 .7 .85\" rgb2=\".1 .15 .2\" width=\"256\" height=\"256\"/>\n"
      "{}"
      "  </asset>\n"
      "  <worldbody>\n"
      "    <light name=\"sun\" directional=\"true\" pos=\"0 0 5\" dir=\"-0.3 -0.3 -1\" diffuse=\".8 .8 .8\"/>\n",
      ch.name, ch.name, num(opts.timestep), opts.max_constraints, opts.max_contacts,
      opts.visual_extent > 0 ? fmt::format("  <statistic extent=\"{}\" center=\"0 0 1\"/>\n", num(opts.visual_extent)) : std::string(),
      num(opts.armature), num(opts.friction), opts.extra_assets);
  xml += opts.extra_worldbody;
  if (opts.floor)
    xml += "    <geom name=\"floor\" type=\"plane\" size=\"100 100 0.1\" material=\"grid\" contype=\"1\" conaffinity=\"1\"/>\n";
  // Bodies nest like the skeleton: emit depth-first with explicit closing tags.
  const auto children = sk.children();
  std::vector<std::pair<int, bool>> stack{{0, false}};  // (joint, closing)
  while (!stack.empty()) {
    const auto [j, closing] = stack.back();
    stack.pop_back();
    const auto ju = static_cast<std::size_t>(j);
    std::string indent(static_cast<std::size_t>(4 + 2 * [&] { int d = 0; for (int p = sk.joints[ju].parent; p >= 0; p = sk.joints[static_cast<std::size_t>(p)].parent) ++d; return d; }()), ' ');
    if (closing) {
      xml += indent + "</body>\n";
      continue;
    }
    const Joint& jt = sk.joints[ju];
    const PdGain& g = ch.gains[ju];
    if (j == 0) {
      xml += indent + fmt::format("<body name=\"{}\" pos=\"0 0 1\">\n", jt.name);
      xml += indent + fmt::format("  <freejoint name=\"{}\"/>\n", jt.name);
    } else {
      xml += indent + fmt::format("<body name=\"{}\" pos=\"{}\" quat=\"{}\">\n", jt.name, vec(jt.offset), quat(jt.rest));
      if (jt.type == JointType::Spherical) {
        xml += indent + fmt::format("  <joint name=\"{}\" type=\"ball\" damping=\"{}\"/>\n", jt.name, num(g.kd));
      } else if (jt.type == JointType::Revolute) {
        std::string range;
        if (!jt.limits.empty()) range = fmt::format(" limited=\"true\" range=\"{} {}\"", num(jt.limits[0].first), num(jt.limits[0].second));
        xml += indent + fmt::format("  <joint name=\"{}\" type=\"hinge\" axis=\"{}\" damping=\"{}\"{}/>\n", jt.name, vec(jt.axis), num(g.kd), range);
      }
    }
    xml += indent + "  " + geom_xml(ch.bodies[ju]) + "\n";
    stack.emplace_back(j, true);
    for (auto it = children[ju].rbegin(); it != children[ju].rend(); ++it) stack.emplace_back(*it, false);
  }
  xml += "  </worldbody>\n</mujoco>\n";
  return xml;
}

}  // namespace mimic
