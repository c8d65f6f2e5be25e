#pragma once
// A clip in time: resampled to another frame rate, or cut to a stretch of it.
#include <string>

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

// A stretch of a clip named on a command line: "FILE@FROM" or "FILE@FROM:TO", in seconds, a
// negative time counting back from the clip's end ("getup.txt@-0.3": its last 0.3 s); "FILE",
// all of it. The times are resolved against the clip by `cut`.
struct ClipStretch {
  std::string file;
  double from = 0.0;
  double to = 0.0;
  bool whole = true;   // no "@": the clip as it is
  bool to_end = true;  // no ":TO": up to the clip's end
};

// Splits `text` at its last '@' (where there is one). Throws Error naming `text` where what
// follows it is not FROM or FROM:TO.
ClipStretch parse_clip_stretch(const std::string& text);

// The clip's frames within the stretch, as `excerpt` (the clip itself for a whole one). Throws
// Error naming the stretch and the clip's duration where the times fall outside it.
Clip cut(const Clip& clip, const ClipStretch& stretch);

}  // namespace mimic
