#pragma once
// The retarget maps built into mimic (data/retarget/*.yaml, compiled in by CMake): named by
// their file's stem, e.g. "cmu_to_humanoid3d", "mixamo_to_humanoid3d". A command's --map takes a
// file or one of these names; without --map, a clip that does not fit a character is retargeted by
// the one built-in map that fits both (map_fits).
#include <string>
#include <vector>

#include "motion/retarget.hpp"

namespace mimic {

struct BuiltinText {
  const char* name;
  const char* text;
};

// Generated: every built-in map's name and text, in name order.
const std::vector<BuiltinText>& builtin_retarget_map_texts();

std::vector<std::string> builtin_retarget_map_names();
// The same, comma-separated (for help texts and errors).
std::string builtin_retarget_map_list();

// Throws Error listing the built-in names when there is none of this name.
RetargetMap builtin_retarget_map(const std::string& name);

// A file when one exists at this path, else the built-in map of this name; an error names both
// possibilities otherwise.
RetargetMap load_retarget_map_or_builtin(const std::string& file_or_name);

// The built-in maps that fit a source skeleton onto a target one, by name.
std::vector<std::string> builtin_maps_fitting(const Skeleton& source, const Skeleton& target);

}  // namespace mimic
