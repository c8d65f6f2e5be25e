#include "motion/resample.hpp"

#include <cmath>

#include "core/error.hpp"

namespace mimic {

Clip resample(const Clip& clip, double fps) {
  if (!(fps > 0.0) || !std::isfinite(fps)) throw Error("resample: frame rate must be positive");
  if (clip.frames.empty()) throw Error("resample: clip '" + clip.name + "' has no frames");
  Clip out;
  out.name = clip.name;
  out.skeleton = clip.skeleton;
  out.loop = clip.loop;
  const double duration = clip.duration();
  long intervals = 0;
  if (clip.loop == LoopMode::Wrap) {
    intervals = std::max(1L, std::lround(duration * fps));
    out.fps = duration > 0 ? static_cast<double>(intervals) / duration : fps;
  } else {
    intervals = static_cast<long>(std::floor(duration * fps + 1e-9));
    out.fps = fps;
  }
  if (intervals > 10'000'000) throw Error("resample: more than 10 million frames");
  out.frames.reserve(static_cast<std::size_t>(intervals + 1));
  for (long k = 0; k < intervals; ++k) out.frames.push_back(clip.sample(static_cast<double>(k) / out.fps));
  // The end of the first cycle (not the start of the next one, which a wrap clip jumps to).
  out.frames.push_back(clip.frames.back());
  return out;
}

}  // namespace mimic
