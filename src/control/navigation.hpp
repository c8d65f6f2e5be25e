#pragma once
// The navigation task by name: `env: {name: navigation, skill: MODEL, terrain: {...}, ...}` is
// env/navigation_env.hpp's high-level controller task over a frozen steered skill, which the
// runtime loads (Skill::load: so it lives here, above the environment layer). The keys:
//   skill           the low-level skill's model or run directory (trained with env.goal: heading)
//   terrain         the course (env.terrain's keys, environments.md), e.g. {kind: walls}
//   decision_steps, max_turn, view_ahead, view_width, view_spacing, progress_weight, max_seconds
//                   NavigationConfig's
// register_control_envs() adds the name to the environment factory; the mimic program and
// Skill::load call it (again is harmless).
namespace mimic {

void register_control_envs();

}  // namespace mimic
