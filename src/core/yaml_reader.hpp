#pragma once
// Reading YAML (and JSON, which yaml-cpp also reads) with errors that name the file, the line
// and the key: every file format and config of mimic that is YAML or JSON goes through this.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>
#include <string_view>

namespace mimic {

// ParseError at the second of two equal keys in one mapping, anywhere under `node` (yaml-cpp
// keeps both and answers the first: `seed: 2` then `seed: 3` would silently train seed 2), and at
// a key that is not a name (`{[512, 256], clip: x}`: a list or mapping as a key, or an empty one).
void check_mapping_keys(const YAML::Node& node, const std::string& source);

class YamlReader {
 public:
  // `quote` surrounds key names in messages: '"' for JSON files, '\'' for YAML.
  explicit YamlReader(std::string source, char quote = '\'') : source_(std::move(source)), quote_(quote) {}

  // Parses `text` (at most kMaxYamlBytes); a syntax error becomes ParseError "<invalid>:
  // <yaml-cpp's message>", a key given twice in one mapping a ParseError naming both lines.
  YAML::Node parse(std::string_view text, const std::string& invalid) const;

  [[noreturn]] void fail(const YAML::Node& at, const std::string& message) const;

  // A required member of a mapping ("<where>: missing 'key'"; null counts as missing).
  YAML::Node member(const YAML::Node& map, const char* key, const std::string& where) const;
  double number(const YAML::Node& n, const std::string& what) const;   // finite
  long integer(const YAML::Node& n, const std::string& what) const;
  std::string text(const YAML::Node& n, const std::string& what) const;  // any scalar
  template <int N>
  Eigen::Matrix<double, N, 1> vec(const YAML::Node& n, const std::string& what) const {
    if (!n.IsSequence() || n.size() != N) fail(n, what + ": expected a list of " + std::to_string(N) + " numbers");
    Eigen::Matrix<double, N, 1> v;
    for (int i = 0; i < N; ++i) v[i] = number(n[static_cast<std::size_t>(i)], what);
    return v;
  }

  // Member shorthands: "<where> 'key'" names the value in messages.
  double number(const YAML::Node& map, const char* key, const std::string& where) const;
  double number_or(const YAML::Node& map, const char* key, const std::string& where, double fallback) const;
  std::string text(const YAML::Node& map, const char* key, const std::string& where) const;
  YAML::Node sequence(const YAML::Node& map, const char* key, const std::string& where) const;

  const std::string& source() const { return source_; }
  std::string quoted(const char* key) const { return quote_ + std::string(key) + quote_; }

 private:
  std::string source_;
  char quote_;
};

}  // namespace mimic
