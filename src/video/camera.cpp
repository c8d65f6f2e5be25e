#include "video/camera.hpp"

#include <cmath>

namespace mimic {

double focal_from_fov(double fov_deg, int height) { return 0.5 * height / std::tan(0.5 * deg_to_rad(fov_deg)); }

PinholeCamera PinholeCamera::looking_at(const Vec3& position, const Vec3& target, double fov_deg, int width, int height) {
  PinholeCamera c;
  c.position = position;
  c.width = width, c.height = height;
  c.focal_px = focal_from_fov(fov_deg, height);
  const Vec3 z = (target - position).normalized();            // along the view
  const Vec3 x = z.cross(Vec3::UnitZ()).normalized();          // right (the world's up is -y)
  const Vec3 y = z.cross(x);                                   // down
  Mat3 m;
  m.col(0) = x, m.col(1) = y, m.col(2) = z;
  c.world_from_camera = Quat(m);
  return c;
}

Vec2 PinholeCamera::project(const Vec3& world) const {
  const Vec3 p = to_camera(world);
  return {0.5 * width + focal_px * p.x() / p.z(), 0.5 * height + focal_px * p.y() / p.z()};
}

}  // namespace mimic
