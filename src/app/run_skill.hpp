#pragma once
// A run or model directory as a runtime skill (docs/runtime.md), for the commands that act with a
// trained policy (eval, render, record, score): its networks.mimic where it has one that is not
// older than its checkpoint.pt (a model written by mimic export), else the checkpoint's networks
// converted in memory (a run directory, an older model, a run trained on after --networks-only).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "control/episodes.hpp"
#include "mimic/runtime.hpp"

namespace mimic::app {

// The networks file's bytes, and the file they come from (named in errors).
struct RunNetworks {
  std::string bytes;
  std::filesystem::path source;
};
// `discriminators`: a conversion keeps the run's discriminators too (score, latency), which needs
// the expert files its config names.
RunNetworks run_networks(const std::filesystem::path& run, bool discriminators = false);
// `env_settings`: env.KEY=VALUE overrides (eval --set). With `discriminators`, a networks.mimic
// exported without them gives way to the checkpoint's conversion where there is one.
std::shared_ptr<const Skill> run_skill(const std::filesystem::path& run, const std::vector<std::string>& env_settings = {},
                                       bool discriminators = false);

// Episodes as the run's training evaluates them: its collect.envs environments side by side on its
// collect.threads threads (the episodes depend on the first, not the second).
EpisodeOptions training_episodes(const std::filesystem::path& run);

}  // namespace mimic::app
