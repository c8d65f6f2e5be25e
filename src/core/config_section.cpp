#include "core/config_section.hpp"

#include <cstdio>

namespace mimic {

namespace {
std::string fmt_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

ConfigSection::ConfigSection(const YamlReader& reader, YAML::Node node, std::string path)
    : reader_(reader), node_(std::move(node)), path_(std::move(path)) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap())
    reader_.fail(node_, (path_.empty() ? std::string("config") : "'" + path_ + "'") + ": expected a mapping of keys to values");
}

std::string ConfigSection::name(const char* key) const { return "'" + (path_.empty() ? std::string(key) : path_ + "." + key) + "'"; }

bool ConfigSection::has(const char* key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node ConfigSection::get(const char* key) {
  known_.insert(key);
  if (!has(key)) return YAML::Node(YAML::NodeType::Undefined);
  return node_[key];
}

double ConfigSection::number(const char* key, double fallback) {
  const YAML::Node n = get(key);
  return n.IsDefined() ? reader_.number(n, name(key)) : fallback;
}

double ConfigSection::number(const char* key, double fallback, double lo, double hi) {
  const YAML::Node n = get(key);
  if (!n.IsDefined()) return fallback;
  const double v = reader_.number(n, name(key));
  if (v < lo || v > hi) reader_.fail(n, name(key) + ": " + n.Scalar() + " is outside [" + fmt_number(lo) + ", " + fmt_number(hi) + "]");
  return v;
}

long ConfigSection::integer(const char* key, long fallback, long lo, long hi) {
  const YAML::Node n = get(key);
  if (!n.IsDefined()) return fallback;
  const long v = reader_.integer(n, name(key));
  if (v < lo || v > hi) reader_.fail(n, name(key) + ": " + n.Scalar() + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

std::uint64_t ConfigSection::seed(const char* key, std::uint64_t fallback) {
  const YAML::Node n = get(key);
  if (!n.IsDefined()) return fallback;
  const long v = reader_.integer(n, name(key));
  if (v < 0) reader_.fail(n, name(key) + ": expected a non-negative integer");
  return static_cast<std::uint64_t>(v);
}

bool ConfigSection::boolean(const char* key, bool fallback) {
  const YAML::Node n = get(key);
  if (!n.IsDefined()) return fallback;
  const std::string s = n.IsScalar() ? n.Scalar() : "";
  if (s == "true" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "no" || s == "off") return false;
  reader_.fail(n, name(key) + ": expected true or false");
}

std::string ConfigSection::text(const char* key, const std::string& fallback) {
  const YAML::Node n = get(key);
  return n.IsDefined() ? reader_.text(n, name(key)) : fallback;
}

std::string ConfigSection::choice(const char* key, const std::string& fallback, const std::vector<std::string>& choices) {
  const YAML::Node n = get(key);
  if (!n.IsDefined()) return fallback;
  const std::string v = reader_.text(n, name(key));
  std::string list;
  for (const auto& c : choices) {
    if (c == v) return v;
    list += (list.empty() ? "" : ", ") + c;
  }
  reader_.fail(n, name(key) + ": '" + v + "' is not one of " + list);
}

std::vector<int> ConfigSection::integers(const char* key, const std::vector<int>& fallback, long lo, long hi) {
  const YAML::Node n = get(key);
  if (!n.IsDefined()) return fallback;
  if (!n.IsSequence()) reader_.fail(n, name(key) + ": expected a list of integers");
  std::vector<int> out;
  for (const auto& item : n) {
    const long v = reader_.integer(item, name(key));
    if (v < lo || v > hi) reader_.fail(item, name(key) + ": " + item.Scalar() + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    out.push_back(static_cast<int>(v));
  }
  return out;
}

std::vector<std::string> ConfigSection::texts(const char* key, const std::vector<std::string>& fallback) {
  const YAML::Node n = get(key);
  if (!n.IsDefined()) return fallback;
  if (!n.IsSequence()) reader_.fail(n, name(key) + ": expected a list of names");
  std::vector<std::string> out;
  for (const auto& item : n) {
    if (!item.IsScalar()) reader_.fail(item, name(key) + ": expected a name");
    out.push_back(item.Scalar());
  }
  return out;
}

YAML::Node ConfigSection::child(const char* key) { return get(key); }

void ConfigSection::finish() const {
  if (!node_.IsMap()) return;
  for (const auto& kv : node_) {
    const std::string key = kv.first.Scalar();
    if (known_.count(key)) continue;
    std::string list;
    for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
    reader_.fail(kv.first, "unknown key " + name(key.c_str()) + " (known here: " + list + ")");
  }
}

}  // namespace mimic
