#pragma once
// Seed 004's motion-matching baseline for switching skills: how near the character's pose is to
// the nearest frame of a skill's clips. Poses are compared as every joint's position in the
// pose's own heading frame (root on the ground below it, facing +X), so where the character is
// and which way it faces do not count.
#include <vector>

#include "motion/clip.hpp"

namespace mimic {

class PoseMatcher {
 public:
  // The clips' frames (one skeleton), copied; throws Error without a frame.
  explicit PoseMatcher(const std::vector<const Clip*>& clips);
  // Mean joint distance (m) from `pose` to the nearest frame.
  double cost(const Pose& pose) const;
  // The clips' own spread: the mean joint distance of their frames from their mean pose (m).
  double spread() const { return spread_; }
  // 1 at a frame of the clips, 0 as far from the nearest frame as a typical frame is from the
  // mean pose, below 0 farther: the figure a switch rule compares with its threshold.
  double readiness(const Pose& pose) const { return 1.0 - cost(pose) / spread_; }

 private:
  Skeleton skeleton_;
  std::vector<std::vector<Vec3>> frames_;  // joint positions in each frame's heading frame
  double spread_ = 1.0;
};

}  // namespace mimic
