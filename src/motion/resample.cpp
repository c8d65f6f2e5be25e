#include "motion/resample.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

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

namespace {
std::string number(double x, bool three_decimals = false) {
  char text[32];
  if (three_decimals) std::snprintf(text, sizeof text, "%.3f", x);
  else std::snprintf(text, sizeof text, "%g", x);
  return text;
}
}  // namespace

Clip excerpt(const Clip& clip, double start, double end) {
  const double duration = clip.duration();
  const std::string what = "excerpt of clip '" + clip.name + "': " + number(start) + " to " + number(end) + " s";
  if (!std::isfinite(start) || !std::isfinite(end) || start < 0 || end > duration + 1e-9 || !(start < end))
    throw Error(what + " is not a stretch of its " + number(duration, true) + " s (0 <= start < end <= duration)");
  const auto first = static_cast<std::size_t>(std::ceil(start * clip.fps - 1e-6));
  const auto last = std::min(clip.frames.size() - 1, static_cast<std::size_t>(std::floor(end * clip.fps + 1e-6)));
  if (last <= first)
    throw Error(what + " holds fewer than two of its frames (at " + number(clip.fps, true) + " Hz)");
  Clip out;
  out.name = clip.name;
  out.skeleton = clip.skeleton;
  out.fps = clip.fps;
  out.loop = LoopMode::None;
  out.frames.assign(clip.frames.begin() + static_cast<std::ptrdiff_t>(first), clip.frames.begin() + static_cast<std::ptrdiff_t>(last) + 1);
  return out;
}

}  // namespace mimic
