#include "video/ground_plane.hpp"

#include <algorithm>
#include <Eigen/Eigenvalues>
#include <cmath>

namespace mimic {

namespace {

constexpr double kSpread = 0.15;   // metres (std) the contacts must spread along a direction to show the slope there
constexpr double kAirborne = 0.03; // metres above the plane: not in contact

}  // namespace

GroundFit fit_ground(const std::vector<std::vector<Vec3>>& frames) {
  const Vec3 level(0, -1, 0);
  GroundFit fit;
  std::vector<Vec3> lowest;
  for (const auto& pos : frames)
    if (!pos.empty()) lowest.push_back(*std::min_element(pos.begin(), pos.end(), [&](const Vec3& a, const Vec3& b) { return a.dot(level) < b.dot(level); }));
  Vec3 up = level;
  std::vector<Vec3> contact = lowest;
  for (int round = 0; round < 3 && contact.size() >= 3; ++round) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : contact) c += v / static_cast<double>(contact.size());
    Mat3 cov = Mat3::Zero();
    for (const Vec3& v : contact) cov += (v - c) * (v - c).transpose();
    const Eigen::SelfAdjointEigenSolver<Mat3> es(cov / static_cast<double>(contact.size()));
    if (std::sqrt(es.eigenvalues()[2]) < kSpread) { fit.fitted = false; break; }
    const Vec3 line = es.eigenvectors().col(2);
    Vec3 normal = std::sqrt(es.eigenvalues()[1]) >= kSpread ? Vec3(es.eigenvectors().col(0)) : Vec3((level - level.dot(line) * line).normalized());
    if (normal.dot(level) < 0) normal = -normal;
    if (normal.dot(level) < std::cos(deg_to_rad(45))) { fit.fitted = false; break; }
    up = normal, fit.fitted = true;
    std::vector<Vec3> next;
    for (const Vec3& v : lowest)
      if ((v - c).dot(up) < kAirborne) next.push_back(v);
    contact = next;
  }
  if (!fit.fitted) up = level;
  fit.up = up;
  fit.pitch_deg = rad_to_deg(std::asin(std::clamp(up.z(), -1.0, 1.0)));  // the view (camera z) against the floor
  const Vec3 forward = (Vec3::UnitZ() - up * up.z()).normalized();
  fit.world_from_camera.row(0) = forward.transpose();
  fit.world_from_camera.row(1) = up.cross(forward).transpose();
  fit.world_from_camera.row(2) = up.transpose();
  return fit;
}

}  // namespace mimic
