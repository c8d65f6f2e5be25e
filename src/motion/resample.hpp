#pragma once
// Resampling a clip to another frame rate: Catmull-Rom cubic for root positions, slerp for
// rotations (Clip::sample). A wrap clip keeps its exact cycle: the new rate is adjusted so that a
// whole number of frames spans the cycle, and the rate actually used is the clip's fps.
#include "motion/clip.hpp"

namespace mimic {

Clip resample(const Clip& clip, double fps);

}  // namespace mimic
