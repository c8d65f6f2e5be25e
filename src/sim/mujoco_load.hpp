#pragma once
// Compiling MJCF text with MuJoCo: the one place mimic loads models (the character World, the
// planar environments). Also routes MuJoCo's warnings to stderr instead of MUJOCO_LOG.TXT.
#include <string>
#include <vector>

struct mjModel_;

namespace mimic {

// The compiled model; throws Error "MuJoCo rejected the model of <what>: <MuJoCo's message>".
mjModel_* compile_mjcf(const std::string& mjcf, const std::string& what);

// The names of the bodies of the model's largest tree under the world (the character: its root
// body and the root's descendants), in body order; the bodies an environment adds beside it
// (projectiles, targets) are not among them. What a trained skill's file records and a world it
// runs in must match.
std::vector<std::string> character_body_names(const mjModel_* m);

}  // namespace mimic
