#pragma once
// Small rigid-body math on Eigen: quaternions (w,x,y,z), Euler angles in a named order,
// rotation vectors, heading (yaw about +Z), swing-twist.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string_view>

namespace mimic {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Mat3 = Eigen::Matrix3d;

constexpr double kPi = 3.14159265358979323846;
constexpr double deg_to_rad(double d) { return d * kPi / 180.0; }
constexpr double rad_to_deg(double r) { return r * 180.0 / kPi; }

// Rotation about a principal axis: 'x', 'y' or 'z' (either case).
Quat axis_rotation(char axis, double angle_rad);

// Unit vector of a principal axis: 'x', 'y' or 'z' (either case).
Vec3 axis_vector(char axis);

// Rotation made by applying elementary rotations in the order the axes are listed, each about the
// *rotating* frame's axis: "ZYX" with angles (a,b,c) is Rz(a)*Ry(b)*Rx(c) — the BVH convention,
// where channels are listed outermost first. Angles in radians; `order` has one axis per angle.
Quat euler_intrinsic(std::string_view order, const double* angles_rad);

// Rotation vector (axis * angle, angle in [0, pi]) of a unit quaternion, and back.
Vec3 quat_to_rotvec(const Quat& q);
Quat rotvec_to_quat(const Vec3& v);

// Angular velocity (rad/s, in the frame q0 is expressed in) turning q0 into q1 over dt.
Vec3 angular_velocity(const Quat& q0, const Quat& q1, double dt);

// Yaw of the frame's +X axis projected on the ground plane (Z up), radians in (-pi, pi].
double heading_angle(const Quat& q);
// Yaw-only rotation of a heading angle.
Quat heading_rotation(double heading_rad);

// Signed angle of the twist of q about the unit `axis` (swing-twist decomposition).
double twist_angle(const Quat& q, const Vec3& axis);

// q with non-negative w (q and -q are the same rotation): a canonical sign for storage.
Quat canonical(const Quat& q);

// Angle of the rotation between two unit quaternions, radians in [0, pi].
double rotation_distance(const Quat& a, const Quat& b);

}  // namespace mimic
