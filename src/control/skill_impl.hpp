#pragma once
// A Skill's constant parts (include/mimic/runtime.hpp), visible to the control layer and its tests.
#include <filesystem>

#include "control/network.hpp"
#include "env/env_factory.hpp"
#include "learn/runtime_format.hpp"
#include "mimic/runtime.hpp"

namespace mimic {

struct Skill::Impl {
  std::string name;
  std::filesystem::path dir;
  EnvFactory factory;  // the environment the skill was trained in (config.yaml's env)
  int frame_size = 0, history = 1, action_size = 0;
  std::vector<ObservationSlice> layout;
  std::vector<std::string> bodies;  // the character's MuJoCo bodies after the world body
  // The observation normaliser as learn/normalizer.hpp applies it (identity before any statistics).
  bool normalise = false;
  Eigen::VectorXd mean, inv_std;
  double clip = 0.0;
  Network policy, value;
  Eigen::VectorXf log_std;
  double iteration = 0, samples = 0;

  // Normalised inputs as float32 rows (the networks' input).
  FloatMatrix normalised(const Eigen::MatrixXd& inputs) const;
};

// The skill held by the arrays of `networks` (a networks.mimic file's path, named in errors),
// without an environment: what the runtime checks in the file alone (the model-reader fuzz
// target's entry). Throws Error naming the file and the problem.
std::unique_ptr<Skill::Impl> read_skill_networks(std::string_view bytes, const std::filesystem::path& networks);

}  // namespace mimic
