#pragma once
// A Skill's constant parts (include/mimic/runtime.hpp), visible to the control layer and its tests.
#include <filesystem>

#include "control/discriminator.hpp"
#include "control/network.hpp"
#include "env/env_factory.hpp"
#include "learn/networks/runtime_format.hpp"
#include "motion/clip.hpp"
#include "mimic/runtime.hpp"

namespace mimic {

struct Skill::Impl {
  std::string name;
  std::filesystem::path dir;
  EnvFactory factory;  // the environment the skill was trained in (config.yaml's env)
  int frame_size = 0, history = 1, action_size = 0;
  std::vector<ObservationSlice> layout;
  std::vector<std::string> bodies;  // the character's MuJoCo bodies after the world body
  // The observation normaliser as learn/networks/normalizer.hpp applies it (identity before any statistics).
  bool normalise = false;
  Eigen::VectorXd mean, inv_std;
  double clip = 0.0;
  Network policy, value;
  Eigen::VectorXf log_std;
  std::vector<SkillDiscriminator> discriminators;  // in the config's order of reward sources
  double iteration = 0, samples = 0;

  // Normalised inputs as float32 rows (the networks' input).
  FloatMatrix normalised(const Eigen::MatrixXd& inputs) const;
};

// A skill from a model directory's config.yaml (with `env_settings` applied) and the bytes of its
// networks file (`networks` names it in errors: the file they were read from, or where they came
// from). What Skill::load does once it has read the file; `mimic eval` gives the bytes of a run's
// checkpoint converted in memory where the directory has no networks.mimic.
std::shared_ptr<const Skill> load_skill(const std::filesystem::path& model_dir, std::string_view networks_bytes,
                                        const std::filesystem::path& networks, const std::string& name,
                                        const std::vector<std::string>& env_settings);
// A skill acting in environments of `factory` (a program's own, as TrainOptions::env_factory) with
// the networks of `networks_bytes` (named `networks` in errors), which must fit them: errors name
// the environment as `environment` and end with `hint`. `dir` is what directory() gives.
std::shared_ptr<const Skill> skill_in(EnvFactory factory, std::string_view networks_bytes, const std::filesystem::path& networks,
                                      const std::string& name, const std::filesystem::path& dir = {},
                                      const std::string& environment = "the environment", const std::string& hint = "");
// A new environment of the skill's (its config's env, settings applied).
inline std::unique_ptr<Env> make_skill_env(const Skill& s) { return s.impl().factory(); }
// The clips the skill's episodes start from (each start group's, in their order), or else its
// environment's reference clip; empty for a skill whose starts come from no clip (or that drives
// no character).
std::vector<std::shared_ptr<const Clip>> skill_clips(const Skill& s);

// The skill held by the arrays of `networks` (a networks.mimic file's path, named in errors),
// without an environment: what the runtime checks in the file alone (the model-reader fuzz
// target's entry). Throws Error naming the file and the problem.
std::unique_ptr<Skill::Impl> read_skill_networks(std::string_view bytes, const std::filesystem::path& networks);

}  // namespace mimic
