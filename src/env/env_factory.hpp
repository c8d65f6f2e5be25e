#pragma once
// Environments by name from a config's `env` section, so that training, evaluation and
// benchmarks build the same environment from the same YAML. Unknown names and keys are errors.
#include <functional>
#include <memory>
#include <string>

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

}  // namespace mimic
