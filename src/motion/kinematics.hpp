#pragma once
// Forward kinematics, finite-difference velocities and the heading frame.
#include <vector>

#include "motion/clip.hpp"

namespace mimic {

// Global frames of every joint and site for one pose.
struct LinkFrames {
  std::vector<Vec3> joint_pos;
  std::vector<Quat> joint_rot;
  std::vector<Vec3> site_pos;
};

// Fills `out` (reusing its storage) with the world frames of `pose` on `sk`.
void forward_kinematics(const Skeleton& sk, const Pose& pose, LinkFrames& out);
LinkFrames forward_kinematics(const Skeleton& sk, const Pose& pose);

// Velocities of one frame: root linear and angular velocity in the world frame, and each joint's
// angular velocity in its own frame (what MuJoCo calls a ball joint's qvel).
struct PoseVelocity {
  Vec3 root_lin = Vec3::Zero();
  Vec3 root_ang = Vec3::Zero();
  std::vector<Vec3> joint_ang;  // size num_joints; entry 0 unused (zero)
};

// Velocities of the motion that goes from pose `a` to pose `b` in `dt` seconds.
PoseVelocity pose_velocity(const Pose& a, const Pose& b, double dt);

// Central differences inside the clip; at the ends one-sided, or across the seam of a wrap clip.
std::vector<PoseVelocity> clip_velocities(const Clip& clip);

// Each joint's fastest turn over the clip, frame to frame (rad/s; the root's entry is 0): what a
// character's servos must reach to play it.
std::vector<double> peak_joint_speeds(const Clip& clip);

// Pose and velocities of a clip at any time t (central difference over one frame either side,
// one-sided at the ends of a non-cyclic clip): an initial state for a simulation.
std::pair<Pose, PoseVelocity> clip_state(const Clip& clip, double t);

// The heading frame of a pose: origin at the root's ground projection, X along the facing
// direction, Z up. Expresses world points and rotations in it.
struct HeadingFrame {
  Vec3 origin = Vec3::Zero();
  Quat yaw = Quat::Identity();

  static HeadingFrame of(const Pose& pose);
  Vec3 to_local(const Vec3& world_point) const { return yaw.conjugate() * (world_point - origin); }
  Vec3 dir_to_local(const Vec3& world_dir) const { return yaw.conjugate() * world_dir; }
  Quat rot_to_local(const Quat& world_rot) const { return yaw.conjugate() * world_rot; }
};

// Lowest Z over all joints and sites over all frames.
double clip_min_height(const Clip& clip);

}  // namespace mimic
