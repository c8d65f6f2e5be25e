#pragma once
// A pose as a flat vector of numbers, what the reconstruction's optimiser moves: the root's
// position (3) and rotation vector (3), then per joint a rotation vector (spherical, 3) or an
// angle (revolute, 1); fixed joints have none. Its length is Skeleton::dof_count(). Forward
// kinematics over it is a template so that Ceres's automatic derivatives go through it.
#include <ceres/rotation.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "motion/clip.hpp"

namespace mimic {

// Offset of each joint's parameters in the vector (-1 for a fixed joint).
std::vector<int> parameter_offsets(const Skeleton& sk);
std::vector<double> pose_to_parameters(const Skeleton& sk, const Pose& pose);
Pose parameters_to_pose(const Skeleton& sk, const double* params);

template <typename T>
using Vec3T = Eigen::Matrix<T, 3, 1>;
template <typename T>
using QuatT = Eigen::Quaternion<T>;

// Each joint's rotation relative to its rest frame (the root's: in the world).
template <typename T>
void local_rotations(const Skeleton& sk, const std::vector<int>& offsets, const T* p, std::vector<QuatT<T>>& local) {
  local.resize(sk.joints.size());
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    const int o = offsets[j];
    if (jt.type == JointType::Fixed || o < 0) {
      local[j] = QuatT<T>::Identity();
    } else if (jt.type == JointType::Revolute) {
      const T half = p[o] * T(0.5);
      using std::cos, std::sin;
      local[j] = QuatT<T>(cos(half), sin(half) * T(jt.axis.x()), sin(half) * T(jt.axis.y()), sin(half) * T(jt.axis.z()));
    } else {  // spherical, or the free root's rotation (its position comes first)
      const T* aa = jt.type == JointType::Free ? p + o + 3 : p + o;
      T q[4];
      ceres::AngleAxisToQuaternion(aa, q);
      local[j] = QuatT<T>(q[0], q[1], q[2], q[3]);
    }
  }
}

// World positions of every joint (then every site) of the pose `p`.
template <typename T>
void pose_positions(const Skeleton& sk, const std::vector<int>& offsets, const T* p, std::vector<Vec3T<T>>& pos,
                    std::vector<QuatT<T>>& scratch_local, std::vector<QuatT<T>>& scratch_world) {
  local_rotations(sk, offsets, p, scratch_local);
  const std::size_t n = sk.joints.size();
  pos.resize(n + sk.sites.size());
  scratch_world.resize(n);
  pos[0] = Vec3T<T>(p[0], p[1], p[2]);
  scratch_world[0] = scratch_local[0];
  for (std::size_t j = 1; j < n; ++j) {
    const Joint& jt = sk.joints[j];
    const auto parent = static_cast<std::size_t>(jt.parent);
    pos[j] = pos[parent] + scratch_world[parent] * jt.offset.cast<T>();
    scratch_world[j] = scratch_world[parent] * jt.rest.cast<T>() * scratch_local[j];
  }
  for (std::size_t s = 0; s < sk.sites.size(); ++s) {
    const auto j = static_cast<std::size_t>(sk.sites[s].joint);
    pos[n + s] = pos[j] + scratch_world[j] * sk.sites[s].offset.cast<T>();
  }
}

}  // namespace mimic
