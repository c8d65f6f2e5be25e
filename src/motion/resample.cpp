#include "motion/resample.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
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

namespace {
// A whole decimal number (and nothing after it), or nothing.
std::optional<double> parse_seconds(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return std::nullopt;
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}
}  // namespace

ClipStretch parse_clip_stretch(const std::string& text) {
  ClipStretch s;
  const std::size_t at = text.rfind('@');
  if (at == std::string::npos) {
    s.file = text;
    return s;
  }
  s.file = text.substr(0, at);
  s.whole = false;
  const std::string times = text.substr(at + 1);
  const std::size_t colon = times.find(':');
  const std::optional<double> from = parse_seconds(times.substr(0, colon));
  const std::optional<double> to = colon == std::string::npos ? std::optional<double>(0.0) : parse_seconds(times.substr(colon + 1));
  if (s.file.empty() || !from || !to)
    throw Error("'" + text + "': expected FILE, FILE@FROM or FILE@FROM:TO (seconds; negative ones count back from the clip's end, "
                "e.g. getup.txt@-0.3 for its last 0.3 s)");
  s.from = *from;
  s.to_end = colon == std::string::npos;
  s.to = s.to_end ? 0.0 : *to;
  return s;
}

Clip cut(const Clip& clip, const ClipStretch& stretch) {
  if (stretch.whole) return clip;
  const double duration = clip.duration();
  const double from = stretch.from < 0 ? duration + stretch.from : stretch.from;
  const double to = stretch.to_end ? duration : stretch.to < 0 ? duration + stretch.to : stretch.to;
  const std::string what = stretch.file + "@" + number(stretch.from) + (stretch.to_end ? "" : ":" + number(stretch.to));
  if (from < -1e-9 || to > duration + 1e-9 || !(from < to))
    throw Error(what + ": " + number(std::max(from, 0.0), true) + " to " + number(to, true) + " s is not a stretch of clip '" + clip.name +
                "', which is " + number(duration, true) + " s long");
  try {
    return excerpt(clip, std::max(from, 0.0), std::min(to, duration));
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  }
}

}  // namespace mimic
