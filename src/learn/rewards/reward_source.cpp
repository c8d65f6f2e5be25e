#include "learn/rewards/reward_source.hpp"

#include "core/config_section.hpp"
#include "core/error.hpp"
#include "learn/rewards/adversarial_reward.hpp"

namespace mimic {

void RewardSource::load_widened(torch::serialize::InputArchive&, int added_contexts) {
  throw Error("the '" + name() + "' reward source's saved state cannot take " + std::to_string(added_contexts) + " context inputs");
}

std::unique_ptr<RewardSource> make_reward_source(const RewardSourceConfig& cfg, const RewardSourceContext& context) {
  const YamlReader r(context.config_source);
  ConfigSection s(r, cfg.options, "rewards");
  s.text("source", "");
  s.number("weight", 1.0);
  if (cfg.source == "env") {
    s.finish();
    return std::make_unique<EnvRewardSource>();
  }
  if (cfg.source == "gail" || cfg.source == "iccgan") return make_adversarial_reward_source(cfg.source, s, r, context);
  r.fail(cfg.options, "'rewards': unknown source '" + cfg.source + "' (known: env, gail, iccgan)");
}

}  // namespace mimic
