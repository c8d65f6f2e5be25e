#pragma once
// Compiling MJCF text with MuJoCo: the one place mimic loads models (the character World, the
// planar environments). Also routes MuJoCo's warnings to stderr instead of MUJOCO_LOG.TXT.
#include <string>

struct mjModel_;

namespace mimic {

// The compiled model; throws Error "MuJoCo rejected the model of <what>: <MuJoCo's message>".
mjModel_* compile_mjcf(const std::string& mjcf, const std::string& what);

}  // namespace mimic
