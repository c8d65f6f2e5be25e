#pragma once
// Environments by name from a config's `env` section, so that training, evaluation and
// benchmarks build the same environment from the same YAML. Unknown names and keys are errors.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "core/config_section.hpp"
#include "core/yaml_reader.hpp"
#include "env/env.hpp"

namespace mimic {

// Builds a fresh, independent environment each call (one per worker slot).
using EnvFactory = std::function<std::unique_ptr<Env>()>;

// `env` is the mapping {name: planar_walker | reacher | humanoid_forward | tracking, ...its options}.
// Checks every key now (and builds one environment) so that errors surface before training.
EnvFactory make_env_factory(const YAML::Node& env, const YamlReader& reader);

// The names make_env_factory knows, for messages and help.
std::string env_names();

// Whether environments of that name simulate a character (imitation, tracking and
// humanoid_forward, imitation's old name): the ones with terrain, pushes and cubes.
bool env_has_character(const std::string& name);

// The env section of a run or model directory's config.yaml (undefined where it has none), with
// the file's reader (for messages naming it, and data paths beside it). Throws Error naming the
// file where it is missing or not YAML.
struct ModelEnvSection {
  YAML::Node env;
  YamlReader reader;
};
ModelEnvSection model_env_section(const std::filesystem::path& dir);

// The env name in a run or model directory's config.yaml; "" where the file has no env name.
// Throws Error naming the file where it is missing or not YAML.
std::string model_env_name(const std::filesystem::path& dir);

// An environment a higher layer provides (the navigation task over a frozen skill needs the
// runtime, in control/): make_env_factory hands it the env section (its keys to read and check;
// the caller finishes the section) and the reader. A name already known keeps its first maker.
using EnvMaker = std::function<EnvFactory(ConfigSection& section, const YamlReader& reader)>;
void register_env(const std::string& name, EnvMaker make);

// A data file named by key `key` of the env section: beside the config when it is there (a run
// or model directory holds its own files), else as given, else under the shared data directory.
// Throws Error naming the key and where it looked.
std::filesystem::path env_data_path(const std::string& given, const char* key, const YamlReader& reader);

}  // namespace mimic
