#pragma once
// A motion clip: poses of one skeleton sampled at a fixed rate.
// Frame i is at time i / fps; the duration is (num_frames - 1) / fps. A looping ("wrap") clip
// repeats: cycle k is the first cycle moved k times by the ground translation that takes the first
// frame's root to the last frame's, without turning (DeepMimic's convention; the last frame need
// not equal the first, the seam is where the clip jumps back). A clip that turns over its cycle
// loops as a polyline of straight cycles: give such a motion as a longer clip.
#include <string>
#include <vector>

#include "motion/skeleton.hpp"

namespace mimic {

// One frame. rot[0] is the root's rotation in the world; rot[j] for j > 0 is joint j's rotation
// relative to its rest frame (identity for fixed joints, about `axis` for revolute ones).
struct Pose {
  Vec3 root_pos = Vec3::Zero();
  std::vector<Quat> rot;
};

enum class LoopMode { None, Wrap };

// Importers refuse clips of more than this many joint rotations (frames x joints, ~1 GB): real
// capture is far below (10 min at 120 Hz of 31 joints is 2.2 M), and a tiny malformed file
// cannot make an importer allocate without bound.
constexpr long kMaxClipRotations = 1L << 25;
// No coordinate of a clip (a root position, a bone offset) lies further than this from the origin,
// in metres: 10 km is beyond any capture volume, and larger values are a unit or file error
// (1e308 would overflow in the simulator). Importers refuse them, naming the line.
constexpr double kMaxCoordinate = 1e4;
// No rotation channel turns further than this, in degrees (unwrapped angles of long captures stay
// far below; 1e308 degrees overflows to infinity in radians). Importers refuse larger ones.
constexpr double kMaxAngleDegrees = 1e6;
// Whether every coordinate of `v` is finite and within kMaxCoordinate.
inline bool plausible_position(const Vec3& v) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= kMaxCoordinate; }
const char* to_string(LoopMode m);

struct Clip {
  std::string name;
  Skeleton skeleton;
  double fps = 30.0;
  LoopMode loop = LoopMode::None;
  std::vector<Pose> frames;

  int num_frames() const { return static_cast<int>(frames.size()); }
  double duration() const;
  // Pose at time t (seconds): cubic (Catmull-Rom) root position, slerp rotations. A wrap clip
  // continues past its ends, accumulating root drift per cycle; otherwise t is
  // clamped to [0, duration].
  Pose sample(double t) const;
  // Throws Error on the first inconsistency (fps, frame sizes, non-unit quaternions, ...).
  void validate() const;
};

// Which side a pose lies on: +1 face up, -1 face down (the root's forward axis, +X, more than 30
// degrees above or below the horizontal), 0 neither (standing, sitting, on its side).
int lying_side(const Pose& pose);
// Whether a clip begins on the ground, as a get-up does: its first frame's root below half the
// highest the root reaches in the clip (a clip that never rises, or has no frames, does not).
bool begins_lying(const Clip& clip);

// The identity pose of a skeleton with the root at `root_pos`.
Pose rest_pose(const Skeleton& sk, const Vec3& root_pos = Vec3::Zero());

// Rotation of a revolute joint's pose quaternion about its axis (radians).
double revolute_angle(const Joint& j, const Quat& q);

}  // namespace mimic
