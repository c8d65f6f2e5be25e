#include "motion/axes.hpp"

#include <cmath>

#include "core/error.hpp"

namespace mimic {

Vec3 signed_axis(std::string_view name) {
  double sign = 1.0;
  if (!name.empty() && (name[0] == '-' || name[0] == '+')) {
    sign = name[0] == '-' ? -1.0 : 1.0;
    name.remove_prefix(1);
  }
  if (name.size() != 1 || std::string_view("xyzXYZ").find(name[0]) == std::string_view::npos)
    throw Error("axis must be x, y or z with an optional sign, got '" + std::string(name) + "'");
  return sign * axis_vector(name[0]);
}

Quat source_to_mimic(const AxisConvention& conv) {
  const Vec3 up = signed_axis(conv.up);
  const Vec3 fwd = signed_axis(conv.forward);
  if (std::abs(up.dot(fwd)) > 0.5)
    throw Error("up axis '" + conv.up + "' and forward axis '" + conv.forward + "' must differ");
  if (!(conv.scale > 0.0) || !std::isfinite(conv.scale)) throw Error("unit scale must be a positive number");
  Mat3 rows;
  rows.row(0) = fwd.transpose();
  rows.row(1) = up.cross(fwd).transpose();
  rows.row(2) = up.transpose();
  return Quat(rows).normalized();
}

}  // namespace mimic
