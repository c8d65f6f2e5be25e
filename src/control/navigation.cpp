#include "control/navigation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "control/skill_impl.hpp"
#include "core/config_override.hpp"
#include "core/error.hpp"
#include "core/math.hpp"
#include "env/env_factory.hpp"
#include "env/navigation_env.hpp"

namespace mimic {

namespace {

// The task's keys: the low-level skill's directory, the controller's settings, and the skill's
// environment settings that put it on the course.
struct NavigationSpec {
  std::filesystem::path skill;
  NavigationConfig config;
  std::vector<std::string> settings;
};

NavigationSpec read_navigation(ConfigSection& s, const YamlReader& reader) {
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
  return {dir, c, settings};
}

std::shared_ptr<const Skill> load_low_level(const NavigationSpec& spec, std::vector<std::string> extra = {}) {
  std::vector<std::string> settings = spec.settings;
  settings.insert(settings.end(), extra.begin(), extra.end());
  try {
    return Skill::load(spec.skill, "", settings);
  } catch (const Error& e) {
    throw KeyError("skill", e.what());
  }
}

EnvFactory navigation(ConfigSection& s, const YamlReader& reader) {
  const NavigationSpec spec = read_navigation(s, reader);
  const NavigationConfig c = spec.config;
  const std::filesystem::path dir = spec.skill;
  const std::shared_ptr<const Skill> skill = load_low_level(spec);
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

bool is_navigation_model(const std::filesystem::path& dir) {
  return std::filesystem::exists(dir / "config.yaml") && model_env_name(dir) == "navigation";
}

Navigator::Navigator(const std::filesystem::path& dir, const std::vector<std::string>& skill_settings) : view_(NavigationConfig{}) {
  if (!is_navigation_model(dir))
    throw Error(dir.string() + ": not a navigation controller (its config.yaml's env is not `name: navigation`)");
  register_control_envs();
  controller_ = Skill::load(dir);  // checks the whole config, and that the networks fit the task
  const ModelEnvSection env = model_env_section(dir);
  ConfigSection section(env.reader, env.env, "env");
  const NavigationSpec spec = read_navigation(section, env.reader);
  skill_ = load_low_level(spec, skill_settings);
  view_ = NavigationView(spec.config);
}

bool Navigator::drive(Controller& c) {
  if (c.steps() % view_.cfg.decision_steps != 0) return false;
  const Eigen::VectorXd frame =
      view_.observe(c.root_position(), c.facing(), [&c](double x, double y) { return c.ground_height(x, y); }, c.course_half_width());
  // The controller's history, oldest first, as training's stacking: a new episode starts it full of its first frame.
  if (c.steps() == 0 || frames_.empty()) frames_.assign(static_cast<std::size_t>(controller_->history()), frame);
  else {
    frames_.pop_front();
    frames_.push_back(frame);
  }
  Eigen::VectorXd input(controller_->input_size());
  for (std::size_t f = 0; f < frames_.size(); ++f) input.segment(static_cast<Eigen::Index>(f) * frame.size(), frame.size()) = frames_[f];
  c.set_heading(view_.command(controller_->act(input)[0]));
  return true;
}
}  // namespace mimic
