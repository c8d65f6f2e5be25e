#include "motion/deepmimic_scale.hpp"

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "core/json_text.hpp"
#include "core/yaml_reader.hpp"
#include "motion/deepmimic.hpp"

namespace mimic {
namespace {

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// JSON text of a node read from JSON: mappings keep their key order; a scalar that was quoted in
// the source (yaml-cpp tags it "!") is written quoted, any other as it stands (numbers, true).
void write_json(const YAML::Node& n, int depth, std::string& out) {
  const std::string indent(static_cast<std::size_t>(2 * (depth + 1)), ' '), close(static_cast<std::size_t>(2 * depth), ' ');
  if (n.IsMap()) {
    out += "{\n";
    bool first = true;
    for (const auto& kv : n) {
      out += (first ? "" : ",\n") + indent + json_quoted(kv.first.Scalar()) + ": ";
      write_json(kv.second, depth + 1, out);
      first = false;
    }
    out += "\n" + close + "}";
  } else if (n.IsSequence()) {
    out += "[\n";
    for (std::size_t i = 0; i < n.size(); ++i) {
      out += (i ? ",\n" : "") + indent;
      write_json(n[i], depth + 1, out);
    }
    out += "\n" + close + "]";
  } else if (n.IsScalar()) {
    out += n.Tag() == "!" ? json_quoted(n.Scalar()) : n.Scalar();
  } else {
    out += "null";
  }
}

// Multiplies the number at map[key] by f (absent keys stay absent).
void times(const YamlReader& js, YAML::Node map, const char* key, double f, const std::string& where) {
  if (!map[key].IsDefined()) return;
  map[key] = YAML::Node(number_text(js.number(map, key, where) * f));
}

void check_factor(double f, const std::string& source, const std::string& what) {
  if (!(f > 0) || !std::isfinite(f)) throw Error(source + ": " + what + " must be a positive number (got " + number_text(f) + ")");
}

}  // namespace

ScaledCharacter scale_deepmimic_character(std::string_view text, const std::string& source, const CharacterScaling& scaling) {
  const DeepMimicCharacter parsed = parse_deepmimic_character(text, source);  // every error of a malformed file
  const Skeleton& sk = parsed.skeleton;
  ScaledCharacter out;
  out.factors.assign(sk.joints.size(), 1.0);
  for (const auto& [part, f] : scaling.lengths) {
    check_factor(f, source, "the length factor of '" + part + "'");
    bool any = false;
    for (std::size_t j = 0; j < sk.joints.size(); ++j)
      if (part == "*" || sk.joints[j].name.find(part) != std::string::npos) out.factors[j] = f, any = true;
    if (!any || part.empty()) throw Error(source + ": no joint's name contains '" + part + "' (a length factor's joint name part)");
  }
  check_factor(scaling.mass, source, "the mass factor");
  if (scaling.gains != 0) check_factor(scaling.gains, source, "the gain factor");
  double mean = 0;
  for (const double f : out.factors) mean += f;
  mean /= static_cast<double>(out.factors.size());
  out.gains = scaling.gains != 0 ? scaling.gains : scaling.mass * mean;

  const YamlReader js(source, '"');
  YAML::Node root = js.parse(text, "not valid JSON");
  YAML::Node joints = root["Skeleton"]["Joints"];
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const std::string where = "joint " + std::to_string(i);
    const int parent = sk.joints[i].parent;
    if (parent >= 0)
      for (const char* key : {"AttachX", "AttachY", "AttachZ"}) times(js, joints[i], key, out.factors[static_cast<std::size_t>(parent)], where);
    times(js, joints[i], "TorqueLim", out.gains, where);
  }
  YAML::Node bodies = root["BodyDefs"];
  for (std::size_t i = 0; bodies.IsSequence() && i < bodies.size(); ++i) {
    const std::string where = "body " + std::to_string(i);
    for (const char* key : {"AttachX", "AttachY", "AttachZ", "Param0", "Param1", "Param2"}) times(js, bodies[i], key, out.factors[i], where);
    times(js, bodies[i], "Mass", scaling.mass, where);
  }
  YAML::Node shapes = root["DrawShapeDefs"];
  for (std::size_t i = 0; shapes.IsSequence() && i < shapes.size(); ++i) {
    const std::string where = "draw shape " + std::to_string(i);
    const long j = js.integer(js.member(shapes[i], "ParentJoint", where), where + " \"ParentJoint\"");
    if (j < 0 || j >= static_cast<long>(sk.joints.size())) js.fail(shapes[i], where + ": \"ParentJoint\" is not a joint's ID");
    for (const char* key : {"AttachX", "AttachY", "AttachZ", "Param0", "Param1", "Param2"})
      times(js, shapes[i], key, out.factors[static_cast<std::size_t>(j)], where);
  }
  write_json(root, 0, out.character);
  out.character += "\n";
  return out;
}

std::string scale_deepmimic_controller(std::string_view text, const std::string& source, double gains) {
  check_factor(gains, source, "the gain factor");
  const YamlReader js(source, '"');
  YAML::Node root = js.parse(text, "not valid JSON");
  if (!root.IsMap()) js.fail(root, "expected a JSON object at the top level");
  YAML::Node ctrls = js.sequence(root, "PDControllers", "controller file");
  for (std::size_t i = 0; i < ctrls.size(); ++i) {
    const std::string where = "PD controller " + std::to_string(i);
    times(js, ctrls[i], "Kp", gains, where);
    times(js, ctrls[i], "Kd", gains, where);
  }
  std::string out;
  write_json(root, 0, out);
  return out + "\n";
}

}  // namespace mimic
