#pragma once
// A YAML config read from its file, with `extends: BASE.yaml` resolved: the base (a path relative
// to the config's directory; it may extend another) with the config's own keys merged over it.
// Mappings merge key by key; any other value replaces the base's; a mapping whose keys are all
// indices of the base's list merges into those elements (`rewards: {0: {expert: demos.csv}}`).
// The result is the fully resolved text, re-emitted under a comment naming the chain, so that a
// run's config.yaml, and a model exported from it, keep their values when a base changes later.
#include <filesystem>
#include <string>

namespace mimic {

// The text of `path` with its `extends` chain resolved (the text as it is when it has none).
// Error naming the file and line for a base that is missing, not a mapping, or a cycle.
std::string read_config_file(const std::filesystem::path& path);

}  // namespace mimic
