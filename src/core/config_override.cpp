#include "core/config_override.hpp"

#include "core/error.hpp"
#include "core/yaml_reader.hpp"

namespace mimic {

std::string flow_yaml(const YAML::Node& node) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  return out.c_str();
}

std::string override_config(const std::string& text, const std::string& source, const std::vector<std::string>& settings) {
  if (settings.empty()) return text;
  const YamlReader r(source);
  YAML::Node root = r.parse(text, "not valid YAML");
  std::string note = "# " + source + " with";
  for (const std::string& setting : settings) {
    const std::size_t eq = setting.find('=');
    if (eq == std::string::npos || eq == 0) throw Error("--set '" + setting + "': expected KEY.PATH=VALUE, e.g. ppo.clip=0.1");
    const std::string path = setting.substr(0, eq);
    YAML::Node value;
    try {
      value = YAML::Load(setting.substr(eq + 1));
      check_mapping_keys(value, "--set '" + setting + "'");
    } catch (const YAML::Exception& e) {
      throw Error("--set '" + setting + "': the value is not valid YAML (" + e.msg + ")");
    }
    YAML::Node cur = root;  // reset() rebinds; operator= would overwrite the node it refers to
    std::size_t start = 0;
    while (true) {
      const std::size_t dot = path.find('.', start);
      const std::string key = path.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
      if (key.empty()) throw Error("--set '" + setting + "': empty key in '" + path + "'");
      YAML::Node next;
      if (cur.IsSequence()) {
        std::size_t index = 0, used = 0;
        try {
          index = std::stoul(key, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == key.size() && index == cur.size() && dot == std::string::npos) {  // one past the end: appended
          cur.push_back(value);
          break;
        }
        if (used != key.size() || index >= cur.size())
          throw Error("--set '" + setting + "': '" + key + "' is not an index of a " + std::to_string(cur.size()) +
                      "-element list (" + std::to_string(cur.size()) + " appends an element)");
        next.reset(cur[index]);
      } else if (cur.IsMap() || cur.IsNull() || !cur.IsDefined()) {  // absent sections are created
        if (dot == std::string::npos) {
          cur[key] = value;
          break;
        }
        next.reset(cur[key]);
      } else {
        throw Error("--set '" + setting + "': '" + path.substr(0, start == 0 ? 0 : start - 1) + "' is a value, not a section");
      }
      if (dot == std::string::npos) {  // the last key named a list element
        next = value;
        break;
      }
      cur.reset(next);
      start = dot + 1;
    }
    note += " " + setting;
  }
  YAML::Emitter out;
  out << root;
  return note + "\n" + out.c_str() + "\n";
}

}  // namespace mimic
