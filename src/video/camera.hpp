#pragma once
// Cameras of the video pipeline. Camera axes are OpenCV's: x right, y down, z along the view.
// Pixels: (0, 0) is the top-left corner of the image, the principal point its centre.
#include "core/math.hpp"
#include "video/keypoints.hpp"

namespace mimic {

// A pinhole camera placed in mimic's world (Z up): what renders and the synthetic benchmark use.
struct PinholeCamera {
  Vec3 position = Vec3::Zero();
  Quat world_from_camera = Quat::Identity();  // the camera's axes expressed in the world
  double focal_px = 1000.0;
  int width = 1280, height = 720;

  // A camera at `position` looking at `target`, its image's up along the world's +Z.
  static PinholeCamera looking_at(const Vec3& position, const Vec3& target, double fov_deg, int width, int height);
  Vec3 to_camera(const Vec3& world) const { return world_from_camera.conjugate() * (world - position); }
  // Pixel of a point in front of the camera (z > 0 in camera axes).
  Vec2 project(const Vec3& world) const;
};

// The focal length in pixels of a vertical field of view over an image `height` pixels high.
double focal_from_fov(double fov_deg, int height);

// The field of view a track is reconstructed with when its file gives none (a phone's or a
// webcam's main camera, about 55 degrees vertically in landscape).
constexpr double kDefaultFovDeg = 55.0;

}  // namespace mimic
