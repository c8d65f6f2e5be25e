#include "app/run_skill.hpp"

#include "control/skill_impl.hpp"
#include "core/file_io.hpp"
#include "learn/networks/runtime_format.hpp"
#include "learn/trainer/train_config.hpp"
#include "learn/trainer/trainer.hpp"

namespace mimic::app {

RunNetworks run_networks(const std::filesystem::path& run, bool discriminators) {
  // A networks.mimic older than the checkpoint (a run trained on after --networks-only) is stale.
  const std::filesystem::path networks = run / kRuntimeFileName, checkpoint = run / "checkpoint.pt";
  if (std::filesystem::exists(networks) &&
      (!std::filesystem::exists(checkpoint) || std::filesystem::last_write_time(networks) >= std::filesystem::last_write_time(checkpoint)))
    return {read_text_file(networks, kMaxCheckpointBytes), networks};
  return {Trainer::from_run(run, discriminators)->runtime_networks(), checkpoint};
}

std::shared_ptr<const Skill> run_skill(const std::filesystem::path& run, const std::vector<std::string>& env_settings, bool discriminators) {
  const RunNetworks n = run_networks(run, discriminators);
  std::shared_ptr<const Skill> skill = load_skill(run, n.bytes, n.source, "", env_settings);
  const std::filesystem::path checkpoint = run / "checkpoint.pt";
  if (discriminators && skill->discriminators().empty() && n.source != checkpoint && std::filesystem::exists(checkpoint))
    skill = load_skill(run, Trainer::from_run(run, true)->runtime_networks(), checkpoint, "", env_settings);
  return skill;
}

EpisodeOptions training_episodes(const std::filesystem::path& run) {
  const std::filesystem::path config = run / "config.yaml";
  const TrainConfig cfg = parse_train_config(read_text_file(config), config.string());
  EpisodeOptions o;
  o.slots = cfg.collect.envs;
  o.threads = cfg.collect.threads;
  return o;
}

}  // namespace mimic::app
