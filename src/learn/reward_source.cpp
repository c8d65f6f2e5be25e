#include "learn/reward_source.hpp"

#include "core/config_section.hpp"
#include "core/error.hpp"

namespace mimic {

std::unique_ptr<RewardSource> make_reward_source(const RewardSourceConfig& cfg, const std::string& config_source) {
  const YamlReader r(config_source);
  ConfigSection s(r, cfg.options, "rewards");
  s.text("source", "");
  s.number("weight", 1.0);
  if (cfg.source == "env") {
    s.finish();
    return std::make_unique<EnvRewardSource>();
  }
  r.fail(cfg.options, "'rewards': unknown source '" + cfg.source + "' (known: env)");
}

}  // namespace mimic
