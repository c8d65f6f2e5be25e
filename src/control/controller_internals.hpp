#pragma once
// What the control layer and the app read of a Controller beyond its public, torch-free interface
// (include/mimic/runtime.hpp), whose types it does not expose.
#include "env/character_env.hpp"
#include "mimic/runtime.hpp"

namespace mimic {

struct ControllerInternals {
  // The active skill's character environment (its world, its character); null where the skill
  // drives no character.
  static const CharacterEnv* active_character(const Controller& c);
  // The active skill's environment.
  static const Env& active_env(const Controller& c);
};

}  // namespace mimic
