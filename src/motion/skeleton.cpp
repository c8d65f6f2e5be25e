#include "motion/skeleton.hpp"

#include <cmath>
#include <set>

#include "core/error.hpp"

namespace mimic {

const char* to_string(JointType t) {
  switch (t) {
    case JointType::Free: return "free";
    case JointType::Spherical: return "spherical";
    case JointType::Revolute: return "revolute";
    case JointType::Fixed: return "fixed";
  }
  return "?";
}

bool parse_joint_type(std::string_view s, JointType& out) {
  for (JointType t : {JointType::Free, JointType::Spherical, JointType::Revolute, JointType::Fixed}) {
    if (s == to_string(t)) {
      out = t;
      return true;
    }
  }
  return false;
}

int Skeleton::find(std::string_view name) const {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int>(i);
  return -1;
}

int Skeleton::find_site(std::string_view name) const {
  for (std::size_t i = 0; i < sites.size(); ++i)
    if (sites[i].name == name) return static_cast<int>(i);
  return -1;
}

int Skeleton::dof_count() const {
  int n = 0;
  for (const Joint& j : joints) {
    switch (j.type) {
      case JointType::Free: n += 6; break;
      case JointType::Spherical: n += 3; break;
      case JointType::Revolute: n += 1; break;
      case JointType::Fixed: break;
    }
  }
  return n;
}

void Skeleton::validate() const {
  if (joints.empty()) throw Error("skeleton has no joints");
  if (joints[0].parent != -1 || joints[0].type != JointType::Free)
    throw Error("joint 0 ('" + joints[0].name + "') must be the free root with no parent");
  std::set<std::string> names;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const Joint& j = joints[i];
    const std::string where = "joint " + std::to_string(i) + " ('" + j.name + "')";
    if (j.name.empty()) throw Error(where + " has an empty name");
    if (!names.insert(j.name).second) throw Error(where + ": duplicate joint name");
    if (i > 0) {
      if (j.parent < 0 || j.parent >= static_cast<int>(i))
        throw Error(where + ": parent " + std::to_string(j.parent) + " must be an earlier joint");
      if (j.type == JointType::Free) throw Error(where + ": only the root may be a free joint");
    }
    if (!j.offset.allFinite() || !j.rest.coeffs().allFinite())
      throw Error(where + ": offset or rest rotation is not finite");
    if (j.offset.cwiseAbs().maxCoeff() > 1e4) throw Error(where + ": offset is beyond 1e4 m (a unit or file error)");
    if (std::abs(j.rest.norm() - 1.0) > 1e-6) throw Error(where + ": rest rotation is not a unit quaternion");
    if (j.type == JointType::Revolute && (!j.axis.allFinite() || std::abs(j.axis.norm() - 1.0) > 1e-6))
      throw Error(where + ": revolute axis is not a unit vector");
  }
  std::set<std::string> site_names;
  for (const Site& s : sites) {
    if (s.joint < 0 || s.joint >= num_joints())
      throw Error("site '" + s.name + "' is attached to joint " + std::to_string(s.joint) + ", which does not exist");
    if (!site_names.insert(s.name).second) throw Error("duplicate site name '" + s.name + "'");
    if (!s.offset.allFinite() || s.offset.cwiseAbs().maxCoeff() > 1e4) throw Error("site '" + s.name + "' has a non-finite offset or one beyond 1e4 m");
  }
}

std::vector<std::vector<int>> Skeleton::children() const {
  std::vector<std::vector<int>> out(joints.size());
  for (std::size_t i = 1; i < joints.size(); ++i)
    out[static_cast<std::size_t>(joints[i].parent)].push_back(static_cast<int>(i));
  return out;
}

}  // namespace mimic
