#pragma once
// Inverse kinematics for retargeting (motion/retarget.hpp): end effectors moved to where the
// scaled source has them, and feet held still on the ground while the source's are in stance.
// Damped least squares (Eigen) over the root's position and the joints between the root and each
// effector, frame by frame, from the pose the rotation transfer gave.
#include <string>
#include <vector>

#include "motion/clip.hpp"

namespace mimic {

// A joint's wanted world position in every frame.
struct EffectorGoal {
  int joint = 0;
  std::vector<Vec3> position;
};

// Stance of a foot from its world positions: frames where it is within `height` of its lowest
// over the clip and moves slower than `speed` horizontally (central differences at `fps`).
std::vector<bool> stance_frames(const std::vector<Vec3>& position, double fps, double height = 0.05, double speed = 0.4);

// Each run of stance frames held at one point: the run's mean position horizontally, its lowest
// height vertically. Frames outside stance are left as they are.
void hold_stance(std::vector<Vec3>& position, const std::vector<bool>& stance);

// Mean horizontal speed (m/s) of `position` over the stance frames (0 with none): sliding.
double stance_sliding(const std::vector<Vec3>& position, const std::vector<bool>& stance, double fps);

// Moves each frame's root position (weighted by `root_weight` against leaving the frame's own)
// and the joints that lie between the root and exactly one goal joint (a shared joint such as
// the chest stays) so that the goal joints reach their positions; revolute joints stay within
// their limits. Returns the largest distance left between a goal and its joint.
double reach_effectors(const Skeleton& sk, std::vector<Pose>& frames, const std::vector<EffectorGoal>& goals, double root_weight = 0.2);

}  // namespace mimic
