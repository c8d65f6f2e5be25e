#pragma once
// The navigation task by name: `env: {name: navigation, skill: MODEL, terrain: {...}, ...}` is
// env/navigation_env.hpp's high-level controller task over a frozen steered skill, which the
// runtime loads (Skill::load: so it lives here, above the environment layer). The keys:
//   skill           the low-level skill's model or run directory (trained with env.goal: heading)
//   terrain         the course (env.terrain's keys, environments.md), e.g. {kind: walls}
//   decision_steps, max_turn, view_ahead, view_width, view_spacing, progress_weight, max_seconds,
//   height_map      NavigationConfig's
// register_control_envs() adds the name to the environment factory; the mimic program and
// Skill::load call it (again is harmless).
//
// A trained controller also drives its skill in a runtime session (`mimic play`): the skill runs
// in a Controller on the controller's course, and a Navigator, called before each control step,
// commands its heading every decision_steps steps from what the Controller's world shows.
#include <deque>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "env/navigation_env.hpp"
#include "mimic/runtime.hpp"

namespace mimic {

void register_control_envs();

// Whether a model or run directory's config.yaml trains the navigation task (env.name).
bool is_navigation_model(const std::filesystem::path& dir);

class Navigator {
 public:
  // The controller of model directory `dir` and its low-level skill, loaded on the controller's
  // course with `skill_settings` added (a session's own, e.g. cubes). Throws Error naming the
  // directory for a model of another task.
  Navigator(const std::filesystem::path& dir, const std::vector<std::string>& skill_settings = {});
  const std::shared_ptr<const Skill>& controller() const { return controller_; }
  const std::shared_ptr<const Skill>& skill() const { return skill_; }
  const NavigationConfig& config() const { return view_.cfg; }
  // Before `c`'s step: at every decision_steps-th step since its reset, the controller's command
  // from the state now (Controller::set_heading). True where it decided.
  bool drive(Controller& c);

 private:
  std::shared_ptr<const Skill> controller_, skill_;
  NavigationView view_;
  std::deque<Eigen::VectorXd> frames_;  // the controller's last decisions' views, oldest first
};

}  // namespace mimic
