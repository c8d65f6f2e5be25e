#pragma once
// Motion the project authors itself, so mimic runs with no data at all: a simple 15-joint
// humanoid (1.7 m, DeepMimic-like tree) and a keyframed jumping jack on it.
#include "motion/clip.hpp"

namespace mimic {

Skeleton builtin_humanoid();
// A 1.2 s looping jumping jack at 30 Hz, keyframed and resampled by Clip::sample.
Clip builtin_jumping_jack();
// A 2 s looping squat at 30 Hz: from standing down to a shallow squat with the arms raised forward
// and back up, the soles on the floor throughout. The feet never leave the ground, so a policy
// learns to keep it standing within minutes on two cores (the demo's clip).
Clip builtin_squat();

}  // namespace mimic
