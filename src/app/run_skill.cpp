#include "app/run_skill.hpp"

#include "control/skill_impl.hpp"
#include "core/file_io.hpp"
#include "learn/runtime_format.hpp"
#include "learn/trainer.hpp"

namespace mimic::app {

std::shared_ptr<const Skill> run_skill(const std::filesystem::path& run, const std::vector<std::string>& env_settings, const Trainer* loaded) {
  // A networks.mimic older than the checkpoint (a run trained on after --networks-only) is stale.
  const std::filesystem::path networks = run / kRuntimeFileName, checkpoint = run / "checkpoint.pt";
  if (std::filesystem::exists(networks) &&
      (!std::filesystem::exists(checkpoint) || std::filesystem::last_write_time(networks) >= std::filesystem::last_write_time(checkpoint)))
    return Skill::load(run, "", env_settings);
  std::unique_ptr<Trainer> own;
  if (!loaded) own = Trainer::load_policy(run), loaded = own.get();
  return load_skill(run, loaded->runtime_networks(), run / "checkpoint.pt", "", env_settings);
}

}  // namespace mimic::app
