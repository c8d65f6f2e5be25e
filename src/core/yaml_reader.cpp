#include "core/yaml_reader.hpp"

#include <map>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/text_scanner.hpp"

namespace mimic {

namespace {
// yaml-cpp's messages may quote a raw byte of the input: keep ours printable.
std::string printable_message(std::string m) {
  for (char& c : m)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return m;
}
}  // namespace

void check_mapping_keys(const YAML::Node& node, const std::string& source) {
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) check_mapping_keys(item, source);
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, int> seen;  // key -> line
  for (const auto& pair : node) {
    const int line = pair.first.Mark().line + 1;
    if (!pair.first.IsScalar())
      throw ParseError(source, line, std::string("a key that is ") + (pair.first.IsNull() ? "empty" : pair.first.IsMap() ? "a mapping" : "a list") +
                                         ", where keys are names");
    const auto [at, fresh] = seen.emplace(pair.first.Scalar(), line);
    if (!fresh)
      throw ParseError(source, line, "key '" + printable_message(pair.first.Scalar()) + "' is given twice (first on line " +
                                         std::to_string(at->second) + "); only one of the values could be used");
    check_mapping_keys(pair.second, source);
  }
}

YAML::Node YamlReader::parse(std::string_view text, const std::string& invalid) const {
  check_input_size(text.size(), kMaxYamlBytes, source_, "YAML and JSON, which take some 60 times their size in memory to read");
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw ParseError(source_, e.mark.line + 1, invalid + ": " + printable_message(e.msg));
  }
  check_mapping_keys(root, source_);
  return root;
}

void YamlReader::fail(const YAML::Node& at, const std::string& message) const {
  throw ParseError(source_, at.IsDefined() ? at.Mark().line + 1 : 0, message);
}

YAML::Node YamlReader::member(const YAML::Node& map, const char* key, const std::string& where) const {
  if (!map.IsMap()) fail(map, where + ": expected " + (quote_ == '"' ? "an object" : "a mapping"));
  YAML::Node n = map[key];
  if (!n.IsDefined() || n.IsNull()) fail(map, where + ": missing " + quoted(key));
  return n;
}

double YamlReader::number(const YAML::Node& n, const std::string& what) const {
  double v = 0.0;
  if (!n.IsScalar() || !parse_double(n.Scalar(), v)) fail(n, what + ": expected a finite number");
  return v;
}

long YamlReader::integer(const YAML::Node& n, const std::string& what) const {
  long v = 0;
  if (!n.IsScalar() || !parse_long(n.Scalar(), v)) fail(n, what + ": expected an integer");
  return v;
}

std::string YamlReader::text(const YAML::Node& n, const std::string& what) const {
  if (!n.IsScalar()) fail(n, what + ": expected a string");
  return n.Scalar();
}

double YamlReader::number(const YAML::Node& map, const char* key, const std::string& where) const {
  return number(member(map, key, where), where + " " + quoted(key));
}

double YamlReader::number_or(const YAML::Node& map, const char* key, const std::string& where, double fallback) const {
  if (!map[key].IsDefined()) return fallback;
  return number(map, key, where);
}

std::string YamlReader::text(const YAML::Node& map, const char* key, const std::string& where) const {
  return text(member(map, key, where), where + " " + quoted(key));
}

YAML::Node YamlReader::sequence(const YAML::Node& map, const char* key, const std::string& where) const {
  YAML::Node n = member(map, key, where);
  if (!n.IsSequence()) fail(n, where + " " + quoted(key) + ": expected " + (quote_ == '"' ? "an array" : "a list"));
  return n;
}

}  // namespace mimic
