#pragma once
// One mapping of a YAML config read key by key: every value has a default, wrong types name the
// key, and finish() rejects keys nobody asked for (a typo must not silently keep a default).
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "core/yaml_reader.hpp"

namespace mimic {

class ConfigSection {
 public:
  // `node` may be undefined or null (an absent section: every key keeps its default).
  // `path` names the section in messages ("ppo", "policy", "" for the top level).
  ConfigSection(const YamlReader& reader, YAML::Node node, std::string path);

  double number(const char* key, double fallback);
  // A number in [lo, hi].
  double number(const char* key, double fallback, double lo, double hi);
  long integer(const char* key, long fallback, long lo, long hi);
  std::uint64_t seed(const char* key, std::uint64_t fallback);
  bool boolean(const char* key, bool fallback);
  std::string text(const char* key, const std::string& fallback);
  // One of `choices`.
  std::string choice(const char* key, const std::string& fallback, const std::vector<std::string>& choices);
  std::vector<int> integers(const char* key, const std::vector<int>& fallback, long lo, long hi);
  std::vector<std::string> texts(const char* key, const std::vector<std::string>& fallback);
  // A nested mapping (undefined when absent); its keys are checked by its own section.
  YAML::Node child(const char* key);
  bool has(const char* key) const;

  // Throws ParseError naming the first key that was not read, and the keys that are known.
  void finish() const;
  std::string name(const char* key) const;  // "ppo.clip"

 private:
  YAML::Node get(const char* key);
  const YamlReader& reader_;
  YAML::Node node_;
  std::string path_;
  std::set<std::string> known_;
};

}  // namespace mimic
