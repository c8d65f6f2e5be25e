#pragma once
// A character's kinematic tree in mimic's conventions: Z up, X forward, Y left, metres, radians.
// Joint j's frame in the world is  F_j = F_parent * Translation(offset_j) * rest_j * q_j
// where q_j is the pose's rotation of joint j (see Pose in clip.hpp). Joint 0 is the root.
#include <string>
#include <utility>
#include <vector>

#include "core/math.hpp"

namespace mimic {

enum class JointType { Free, Spherical, Revolute, Fixed };

const char* to_string(JointType t);
// Parses "free", "spherical", "revolute" or "fixed"; false if unknown.
bool parse_joint_type(std::string_view s, JointType& out);

struct Joint {
  std::string name;
  int parent = -1;
  JointType type = JointType::Spherical;
  Vec3 offset = Vec3::Zero();     // origin in the parent joint's frame, metres
  Quat rest = Quat::Identity();   // fixed rotation of this frame relative to the parent's
  Vec3 axis = Vec3::UnitZ();      // rotation axis of a revolute joint, in its own frame
  // Per degree of freedom (spherical: about x, y, z; revolute: the angle), radians; may be empty.
  std::vector<std::pair<double, double>> limits;
  double torque_limit = 0.0;      // N m; 0 when the source gives none
  bool end_effector = false;
};

// A named point rigidly attached to a joint (BVH end sites, tips of leaf bones, body centres).
struct Site {
  std::string name;
  int joint = 0;
  Vec3 offset = Vec3::Zero();  // in the joint's frame
};

class Skeleton {
 public:
  std::vector<Joint> joints;
  std::vector<Site> sites;

  int num_joints() const { return static_cast<int>(joints.size()); }
  // Index of a joint by name, or -1.
  int find(std::string_view name) const;
  // Index of a site by name, or -1.
  int find_site(std::string_view name) const;
  // Degrees of freedom: 6 for the free root, 3 per spherical, 1 per revolute joint.
  int dof_count() const;
  // Throws Error describing the first problem: no joints, root not free, a parent that does not
  // precede its child, duplicate names, a revolute axis that is not a unit vector, bad sites.
  void validate() const;
  // Children of each joint.
  std::vector<std::vector<int>> children() const;
};

}  // namespace mimic
