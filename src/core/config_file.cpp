#include "core/config_file.hpp"

#include <algorithm>
#include <vector>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/yaml_reader.hpp"

namespace mimic {

namespace {

constexpr int kMaxDepth = 8;

// `over` merged onto `base` (both already parsed); `where` names the key path for errors.
YAML::Node merged(const YAML::Node& base, const YAML::Node& over) {
  if (base.IsMap() && over.IsMap()) {
    YAML::Node out = YAML::Clone(base);
    for (const auto& kv : over) {
      const std::string key = kv.first.Scalar();
      out[key] = out[key].IsDefined() ? merged(out[key], kv.second) : YAML::Clone(kv.second);
    }
    return out;
  }
  if (base.IsSequence() && over.IsMap() && over.size() > 0) {
    const bool indices = std::all_of(over.begin(), over.end(), [&](const auto& kv) {
      const std::string& k = kv.first.Scalar();
      return !k.empty() && k.size() < 6 && std::all_of(k.begin(), k.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
             std::stoul(k) < base.size();
    });
    if (indices) {
      YAML::Node out = YAML::Clone(base);
      for (const auto& kv : over) {
        const std::size_t i = std::stoul(kv.first.Scalar());
        out[i] = merged(out[i], kv.second);
      }
      return out;
    }
  }
  return YAML::Clone(over);
}

// `root` (parsed from `path`) with its `extends` chain merged under it.
YAML::Node resolve(const std::filesystem::path& path, YAML::Node root, std::vector<std::filesystem::path>& chain,
                   std::vector<std::string>& names) {
  const YamlReader r(path.string());
  if (!root.IsMap() || !root["extends"].IsDefined()) return root;
  const YAML::Node base_name = root["extends"];
  if (!base_name.IsScalar() || base_name.Scalar().empty()) r.fail(base_name, "'extends' names one base config file (a path)");
  const std::filesystem::path base_path = path.parent_path() / base_name.Scalar(), base = std::filesystem::weakly_canonical(base_path);
  if (std::find(chain.begin(), chain.end(), base) != chain.end())
    r.fail(base_name, "'extends: " + base_name.Scalar() + "' comes back to a config already in the chain");
  if (chain.size() >= static_cast<std::size_t>(kMaxDepth)) r.fail(base_name, "'extends' chains more than 8 configs");
  if (!std::filesystem::is_regular_file(base)) r.fail(base_name, "'extends': " + base.string() + " not found (a path from this config's directory)");
  chain.push_back(base);
  names.push_back(base_path.lexically_normal().string());
  const YAML::Node base_root =
      resolve(base_path, YamlReader(base_path.string()).parse(read_text_file(base_path, kMaxYamlBytes), "not valid YAML"), chain, names);
  if (!base_root.IsMap()) r.fail(base_name, "'extends': " + base.string() + " is not a mapping of sections");
  root.remove("extends");
  return merged(base_root, root);
}

}  // namespace

std::string read_config_file(const std::filesystem::path& path) {
  const std::string text = read_text_file(path, kMaxYamlBytes);
  const YAML::Node root = YamlReader(path.string()).parse(text, "not valid YAML");
  if (!root.IsMap() || !root["extends"].IsDefined()) return text;
  std::vector<std::filesystem::path> chain{std::filesystem::weakly_canonical(path)};
  std::vector<std::string> names;  // the bases as this config's directory reaches them
  const YAML::Node resolved = resolve(path, root, chain, names);
  std::string note = "# " + path.string();
  for (const std::string& name : names) note += " extending " + name;
  YAML::Emitter out;
  out << resolved;
  return note + " (resolved: the bases' keys with this config's merged over them)\n" + out.c_str() + "\n";
}

}  // namespace mimic
