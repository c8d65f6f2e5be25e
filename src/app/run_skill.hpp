#pragma once
// A run or model directory as a runtime skill (docs/runtime.md), for the commands that act with a
// trained policy (eval, render): its networks.mimic where it has one that is not older than its
// checkpoint.pt (a model written by mimic export), else the checkpoint's networks converted in
// memory (a run directory, an older model, a run trained on after --networks-only).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mimic/runtime.hpp"

namespace mimic {
class Trainer;
}

namespace mimic::app {

// `env_settings`: env.KEY=VALUE overrides (eval --set). `loaded`: the run's trainer where the
// caller has one already (saves loading it again when the directory has no networks.mimic).
std::shared_ptr<const Skill> run_skill(const std::filesystem::path& run, const std::vector<std::string>& env_settings = {},
                                       const Trainer* loaded = nullptr);

}  // namespace mimic::app
