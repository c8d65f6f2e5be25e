#include "motion/retarget_maps.hpp"

#include <filesystem>
#include <optional>

#include "core/error.hpp"

namespace mimic {

std::vector<std::string> builtin_retarget_map_names() {
  std::vector<std::string> names;
  for (const BuiltinText& m : builtin_retarget_map_texts()) names.emplace_back(m.name);
  return names;
}

std::string builtin_retarget_map_list() {
  std::string out;
  for (const std::string& n : builtin_retarget_map_names()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

namespace {
// The built-in map of this name, parsed; none where there is no such map.
std::optional<RetargetMap> find_builtin(const std::string& name) {
  for (const BuiltinText& m : builtin_retarget_map_texts())
    if (name == m.name) return parse_retarget_map(m.text, "built-in map " + name);
  return std::nullopt;
}
}  // namespace

RetargetMap builtin_retarget_map(const std::string& name) {
  if (std::optional<RetargetMap> map = find_builtin(name)) return *map;
  throw Error("no built-in retarget map '" + name + "' (built in: " + builtin_retarget_map_list() + ")");
}

RetargetMap load_retarget_map_or_builtin(const std::string& file_or_name) {
  if (std::filesystem::exists(file_or_name)) return load_retarget_map(file_or_name);
  if (std::optional<RetargetMap> map = find_builtin(file_or_name)) return *map;
  throw Error(file_or_name + ": no such map file, nor a built-in map (built in: " + builtin_retarget_map_list() + ")");
}

std::vector<std::string> builtin_maps_fitting(const Skeleton& source, const Skeleton& target) {
  std::vector<std::string> out;
  for (const BuiltinText& m : builtin_retarget_map_texts())
    if (map_fits(parse_retarget_map(m.text, m.name), source, target)) out.emplace_back(m.name);
  return out;
}

}  // namespace mimic
