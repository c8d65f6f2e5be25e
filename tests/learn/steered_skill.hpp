#pragma once
// An untrained skill on DeepMimic's humanoid, with or without a heading goal, as a model
// directory the runtime loads (its config and networks.mimic): what steering and navigation tests
// act with where the policy's quality does not matter.
#include <memory>
#include <string>

#include "core/file_io.hpp"
#include "learn/networks/runtime_export.hpp"
#include "learn/trainer/trainer.hpp"
#include "mimic/runtime.hpp"
#include "../test_data.hpp"

namespace mimic::test {

// Made once a process for each kind (a trainer takes seconds to build under the sanitizers).
inline std::filesystem::path steered_skill_dir(bool goal) {
  static std::filesystem::path made[2];
  std::filesystem::path& dir = made[goal ? 1 : 0];
  if (!dir.empty()) return dir;
  const std::string name = goal ? "steered" : "unsteered";
  const std::string text = std::string("seed: 2\niterations: 1\nenv: {name: imitation, init: fixed") + (goal ? ", goal: heading" : "") +
                           "}\ncollect: {envs: 1, threads: 1, samples: 64}\npolicy: {hidden: [8], activation: relu}\n"
                           "value: {hidden: [8], activation: relu}\nrewards: [{source: env}]\n";
  Trainer trainer(parse_train_config(text, name + ".yaml"));
  const auto made_dir = temp_dir("steering_" + name);
  write_file_atomic(made_dir / "config.yaml", text);
  trainer.write_runtime_networks(made_dir / kRuntimeFileName);
  dir = made_dir;
  return dir;
}

inline std::shared_ptr<const Skill> steered_skill(bool goal, const std::string& name) { return Skill::load(steered_skill_dir(goal), name); }

}  // namespace mimic::test
