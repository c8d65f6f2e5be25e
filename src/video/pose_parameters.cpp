#include "video/pose_parameters.hpp"

namespace mimic {

std::vector<int> parameter_offsets(const Skeleton& sk) {
  std::vector<int> out;
  int at = 0;
  for (const Joint& j : sk.joints) {
    switch (j.type) {
      case JointType::Free: out.push_back(at), at += 6; break;
      case JointType::Spherical: out.push_back(at), at += 3; break;
      case JointType::Revolute: out.push_back(at), at += 1; break;
      case JointType::Fixed: out.push_back(-1); break;
    }
  }
  return out;
}

std::vector<double> pose_to_parameters(const Skeleton& sk, const Pose& pose) {
  std::vector<double> p(static_cast<std::size_t>(sk.dof_count()), 0.0);
  const std::vector<int> off = parameter_offsets(sk);
  for (std::size_t j = 0; j < sk.joints.size(); ++j) {
    const Joint& jt = sk.joints[j];
    const auto o = static_cast<std::size_t>(off[j]);
    if (jt.type == JointType::Free) {
      const Vec3 r = quat_to_rotvec(pose.rot[j]);
      for (int i = 0; i < 3; ++i) p[o + static_cast<std::size_t>(i)] = pose.root_pos[i], p[o + 3 + static_cast<std::size_t>(i)] = r[i];
    } else if (jt.type == JointType::Spherical) {
      const Vec3 r = quat_to_rotvec(pose.rot[j]);
      for (int i = 0; i < 3; ++i) p[o + static_cast<std::size_t>(i)] = r[i];
    } else if (jt.type == JointType::Revolute) {
      p[o] = revolute_angle(jt, pose.rot[j]);
    }
  }
  return p;
}

Pose parameters_to_pose(const Skeleton& sk, const double* params) {
  Pose pose;
  const std::vector<int> off = parameter_offsets(sk);
  local_rotations(sk, off, params, pose.rot);
  for (Quat& q : pose.rot) q = canonical(q.normalized());
  pose.root_pos = Vec3(params[0], params[1], params[2]);
  return pose;
}

}  // namespace mimic
