#pragma once
// How near a pose is to the nearest frame of a skill's clips, and which frame that is: seed 004's
// motion-matching baseline for switching skills, and seed 003 §8's motion completion. Poses are compared as every joint's position in the
// pose's own heading frame (root on the ground below it, facing +X), so where the character is
// and which way it faces do not count (nor, with MatchHeights::RootRelative, its height).
#include <vector>

#include "motion/clip.hpp"

namespace mimic {

// A frame of the matcher's clips and its distance from a pose.
struct FrameMatch {
  int clip = 0;          // in the order the matcher was given them
  int frame = 0;
  double distance = 0;   // mean joint distance (m)
};

// Whether poses are compared at their heights above the ground (a character's pose in a world),
// or with their roots at one height (a pose from a still, whose floor is not seen).
enum class MatchHeights { Absolute, RootRelative };

class PoseMatcher {
 public:
  // The clips' frames (one skeleton), copied; throws Error without a frame.
  explicit PoseMatcher(const std::vector<const Clip*>& clips, MatchHeights heights = MatchHeights::Absolute);
  // Mean joint distance (m) from `pose` to the nearest frame.
  double cost(const Pose& pose) const { return nearest(pose).distance; }
  // The nearest frame (the first of equals). Throws Error for a pose of another skeleton.
  FrameMatch nearest(const Pose& pose) const;
  // The clips' own spread: the mean joint distance of their frames from their mean pose (m).
  double spread() const { return spread_; }
  // 1 at a frame of the clips, 0 as far from the nearest frame as a typical frame is from the
  // mean pose, below 0 farther: the figure a switch rule compares with its threshold.
  double readiness(const Pose& pose) const { return 1.0 - cost(pose) / spread_; }

 private:
  Skeleton skeleton_;
  MatchHeights heights_ = MatchHeights::Absolute;
  std::vector<std::vector<Vec3>> frames_;  // joint positions in each frame's heading frame
  std::vector<FrameMatch> where_;           // each of frames_'s clip and frame
  double spread_ = 1.0;
};

}  // namespace mimic
