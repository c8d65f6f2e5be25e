#include "motion/clip.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace mimic {

const char* to_string(LoopMode m) { return m == LoopMode::Wrap ? "wrap" : "none"; }

double Clip::duration() const {
  return frames.size() < 2 ? 0.0 : static_cast<double>(frames.size() - 1) / fps;
}

int lying_side(const Pose& pose) {
  if (pose.rot.empty()) return 0;
  const double up = (pose.rot[0] * Vec3::UnitX()).z();  // sin of the forward axis's elevation
  return up > 0.5 ? 1 : up < -0.5 ? -1 : 0;
}

bool begins_lying(const Clip& clip) {
  if (clip.frames.empty()) return false;
  double highest = clip.frames.front().root_pos.z();
  for (const Pose& f : clip.frames) highest = std::max(highest, f.root_pos.z());
  return clip.frames.front().root_pos.z() < 0.5 * highest;
}

Pose rest_pose(const Skeleton& sk, const Vec3& root_pos) {
  Pose p;
  p.root_pos = root_pos;
  p.rot.assign(sk.joints.size(), Quat::Identity());
  return p;
}

double revolute_angle(const Joint& j, const Quat& q) { return twist_angle(q, j.axis); }

void Clip::validate() const {
  skeleton.validate();
  if (!(fps > 0.0) || !std::isfinite(fps)) throw Error("clip '" + name + "': frame rate must be positive");
  if (frames.empty()) throw Error("clip '" + name + "' has no frames");
  const std::size_t nj = skeleton.joints.size();
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const Pose& p = frames[f];
    const std::string where = "clip '" + name + "' frame " + std::to_string(f);
    if (p.rot.size() != nj)
      throw Error(where + ": has " + std::to_string(p.rot.size()) + " rotations, skeleton has " +
                  std::to_string(nj) + " joints");
    if (!plausible_position(p.root_pos)) throw Error(where + ": root position is not finite or beyond 1e4 m of the origin");
    for (std::size_t j = 0; j < nj; ++j) {
      if (!p.rot[j].coeffs().allFinite() || std::abs(p.rot[j].norm() - 1.0) > 1e-4)
        throw Error(where + ": rotation of joint '" + skeleton.joints[j].name + "' is not a unit quaternion");
    }
  }
}

namespace {

// The ground translation that takes a wrap clip's first root position to its last: cycle k is the
// first cycle moved k times by it. Translation only, as DeepMimic (cKinCharacter's cycle root
// delta): the run and walk clips run straight (their lateral root coordinate is 0 in every frame)
// but their last frame faces 5.3 and 6.9 degrees off the first, so a turn per cycle taken from the
// end frames' headings bent their loops into circles of some 30 m and 10 m radius.
struct CycleShift {
  Vec3 delta = Vec3::Zero();  // ground plane

  Pose apply(const Pose& p, int times) const {
    Pose out = p;
    out.root_pos += static_cast<double>(times) * delta;
    return out;
  }
};

CycleShift cycle_shift(const Clip& c) {
  const Vec3 d = c.frames.back().root_pos - c.frames.front().root_pos;
  return CycleShift{Vec3(d.x(), d.y(), 0.0)};
}

// Frame i of one cycle for i in [-1, n]: the clip's own frames, and beyond the ends the
// neighbouring cycle's frames (wrap clips) or linearly extrapolated root positions (others).
Pose frame_at(const Clip& c, const CycleShift& shift, long i) {
  const long n = c.num_frames();
  if (i >= 0 && i < n) return c.frames[static_cast<std::size_t>(i)];
  const bool before = i < 0;
  if (c.loop == LoopMode::Wrap && n > 2) {
    return before ? shift.apply(c.frames[static_cast<std::size_t>(n - 2)], -1) : shift.apply(c.frames[1], 1);
  }
  const Pose& edge = c.frames[before ? 0 : static_cast<std::size_t>(n - 1)];
  const Pose& inner = c.frames[before ? std::min<std::size_t>(1, static_cast<std::size_t>(n - 1)) : static_cast<std::size_t>(std::max(0L, n - 2))];
  Pose p = edge;
  p.root_pos = 2.0 * edge.root_pos - inner.root_pos;
  return p;
}

Vec3 catmull_rom(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double u) {
  const double u2 = u * u, u3 = u2 * u;
  return 0.5 * ((2.0 * p1) + (-p0 + p2) * u + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * u2 +
                (-p0 + 3.0 * p1 - 3.0 * p2 + p3) * u3);
}

}  // namespace

Pose Clip::sample(double t) const {
  if (frames.empty()) throw Error("clip '" + name + "' has no frames to sample");
  if (frames.size() == 1 || !std::isfinite(t)) return frames.front();
  const double dur = duration();
  // Wrap clips: whole cycles k are the first cycle displaced k times by the cycle shift.
  long cycles = 0;
  if (loop == LoopMode::Wrap) {
    cycles = static_cast<long>(std::clamp(std::floor(t / dur), -1e6, 1e6));
    t -= static_cast<double>(cycles) * dur;
  }
  const double x = std::clamp(t * fps, 0.0, static_cast<double>(frames.size() - 1));
  const long i = std::min(static_cast<long>(std::floor(x)), static_cast<long>(frames.size()) - 2);
  const double u = x - static_cast<double>(i);
  const CycleShift shift = loop == LoopMode::Wrap ? cycle_shift(*this) : CycleShift{};
  const Pose p0 = frame_at(*this, shift, i - 1), p1 = frame_at(*this, shift, i);
  const Pose p2 = frame_at(*this, shift, i + 1), p3 = frame_at(*this, shift, i + 2);
  Pose out;
  out.root_pos = catmull_rom(p0.root_pos, p1.root_pos, p2.root_pos, p3.root_pos, u);
  out.rot.resize(p1.rot.size());
  for (std::size_t j = 0; j < p1.rot.size(); ++j) out.rot[j] = p1.rot[j].slerp(u, p2.rot[j]).normalized();
  return cycles == 0 ? out : shift.apply(out, static_cast<int>(cycles));
}

}  // namespace mimic
