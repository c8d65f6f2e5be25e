#include "control/navigation.hpp"

#include <string>

#include "control/skill_impl.hpp"
#include "core/config_override.hpp"
#include "core/error.hpp"
#include "env/navigation_env.hpp"

namespace mimic {

namespace {

EnvFactory navigation(ConfigSection& s, const YamlReader& reader) {
  const std::string given = s.text("skill", "");
  if (given.empty()) throw KeyError("skill", "the low-level skill's model directory is needed (a skill trained with env.goal: heading)");
  const std::filesystem::path dir = env_data_path(given, "skill", reader);
  NavigationConfig c;
  c.decision_steps = static_cast<int>(s.integer("decision_steps", c.decision_steps, 1, 10'000));
  c.max_turn = s.number("max_turn", c.max_turn, 1e-3, 180);
  c.view_ahead = s.number("view_ahead", c.view_ahead, 1e-3, 1e3);
  c.view_width = s.number("view_width", c.view_width, 1e-3, 1e3);
  c.view_spacing = s.number("view_spacing", c.view_spacing, 1e-3, 1e3);
  c.progress_weight = s.number("progress_weight", c.progress_weight, 0, 1e6);
  c.max_seconds = s.number("max_seconds", c.max_seconds, 1e-3, 1e6);
  c.height_map = s.boolean("height_map", c.height_map);
  // The skill's own environment on the course, its targets only the controller's, its episodes
  // longer than the controller's.
  std::vector<std::string> settings{"env.goal_period=1000000", "env.max_seconds=" + std::to_string(c.max_seconds + 1.0)};
  const YAML::Node terrain = s.child("terrain");
  if (terrain.IsDefined()) settings.push_back("env.terrain=" + flow_yaml(terrain));
  std::shared_ptr<const Skill> skill;
  try {
    skill = Skill::load(dir, "", settings);
  } catch (const Error& e) {
    throw KeyError("skill", e.what());
  }
  // (make_env_factory builds one now, so a skill that does not fit is an error at the config.)
  return [skill, c, dir] {
    std::unique_ptr<Env> env = make_skill_env(*skill);
    if (!dynamic_cast<CharacterEnv*>(env.get()))
      throw KeyError("skill", dir.string() + ": the low-level skill must drive a character in its own environment (no behaviour context)");
    std::unique_ptr<CharacterEnv> character(dynamic_cast<CharacterEnv*>(env.release()));
    return std::unique_ptr<Env>(std::make_unique<NavigationEnv>(
        std::move(character), [skill](const Eigen::VectorXd& input) { return skill->act(input); }, skill->history(), c));
  };
}

}  // namespace

void register_control_envs() { register_env("navigation", navigation); }

}  // namespace mimic
