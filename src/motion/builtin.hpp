#pragma once
// Motion the project authors itself, so mimic runs with no data at all: a simple 15-joint
// humanoid (1.7 m, DeepMimic-like tree) and a keyframed jumping jack on it.
#include "motion/clip.hpp"

namespace mimic {

Skeleton builtin_humanoid();
// A 1.2 s looping jumping jack at 30 Hz, keyframed and resampled by Clip::sample.
Clip builtin_jumping_jack();

}  // namespace mimic
