#include "core/math.hpp"

#include <cmath>

#include "core/error.hpp"

namespace mimic {

Vec3 axis_vector(char axis) {
  switch (axis) {
    case 'x': case 'X': return Vec3::UnitX();
    case 'y': case 'Y': return Vec3::UnitY();
    case 'z': case 'Z': return Vec3::UnitZ();
    default: throw Error(std::string("unknown rotation axis '") + axis + "'");
  }
}

Quat axis_rotation(char axis, double angle_rad) {
  return Quat(Eigen::AngleAxisd(angle_rad, axis_vector(axis)));
}

Quat euler_intrinsic(std::string_view order, const double* angles_rad) {
  Quat q = Quat::Identity();
  for (std::size_t i = 0; i < order.size(); ++i) q = q * axis_rotation(order[i], angles_rad[i]);
  return q.normalized();
}

Vec3 quat_to_rotvec(const Quat& q_in) {
  Quat q = canonical(q_in);
  const double s = q.vec().norm();
  if (s < 1e-12) return 2.0 * q.vec();  // first order: angle ~ 2*sin(angle/2)
  const double angle = 2.0 * std::atan2(s, q.w());
  return q.vec() * (angle / s);
}

Quat rotvec_to_quat(const Vec3& v) {
  const double angle = v.norm();
  if (angle < 1e-12) return Quat(1.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z()).normalized();
  return Quat(Eigen::AngleAxisd(angle, v / angle));
}

Vec3 angular_velocity(const Quat& q0, const Quat& q1, double dt) {
  // q1 = dq * q0 with dq in the outer frame.
  return quat_to_rotvec(q1 * q0.conjugate()) / dt;
}

double heading_angle(const Quat& q) {
  const Vec3 fwd = q * Vec3::UnitX();
  return std::atan2(fwd.y(), fwd.x());
}

Quat heading_rotation(double heading_rad) { return axis_rotation('z', heading_rad); }

double twist_angle(const Quat& q_in, const Vec3& axis) {
  const Quat q = canonical(q_in);
  const double proj = q.vec().dot(axis);
  return 2.0 * std::atan2(proj, q.w());
}

Quat canonical(const Quat& q) {
  return q.w() < 0.0 ? Quat(-q.w(), -q.x(), -q.y(), -q.z()) : q;
}

double rotation_distance(const Quat& a, const Quat& b) {
  // atan2 form: accurate for tiny angles, where acos of a dot product near 1 is not.
  const Quat d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

}  // namespace mimic
