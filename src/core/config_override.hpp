#pragma once
// `--set KEY.PATH=VALUE` applied to a YAML config: what mimic train, eval and the runtime's
// Skill::load share, so that one setting means the same thing everywhere.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace mimic {

// A node as one line of flow YAML ("{kind: walls, redraw: true}"): what a setting's value takes.
std::string flow_yaml(const YAML::Node& node);

// The config text with `settings` ("ppo.clip=0.1", "rewards.0.episodes=10": keys and list
// indices joined by dots, the value in YAML; a list's size as the last index appends: with one
// reward source, "rewards.1={source: env}" adds a second) applied, re-emitted as YAML under a comment that
// lists them; Error naming the setting when a path does not fit the config. The text itself when
// there is no setting.
std::string override_config(const std::string& text, const std::string& source, const std::vector<std::string>& settings);

}  // namespace mimic
