#pragma once
// A clip in time: resampled to another frame rate, or cut to a stretch of it.
#include "motion/clip.hpp"

namespace mimic {

// Resampling: Catmull-Rom cubic for root positions, slerp for rotations (Clip::sample). A wrap
// clip keeps its exact cycle: the new rate is adjusted so that a whole number of frames spans the
// cycle, and the rate actually used is the clip's fps.
Clip resample(const Clip& clip, double fps);

// The frames from `start` to `end` seconds (those whose times lie in [start, end]), as a clip that
// does not loop: the stretch of a long capture to imitate, or the end of a get-up to start from.
// Throws Error naming the clip for times outside it or a stretch of fewer than two frames.
Clip excerpt(const Clip& clip, double start, double end);

}  // namespace mimic
