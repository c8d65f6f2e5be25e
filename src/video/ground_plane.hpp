#pragma once
// Where the floor is, seen from the camera: for a motion reconstructed in the camera's frame
// (video/reconstruct.hpp), the plane the feet stand on and the world axes it gives.
#include <vector>

#include "core/math.hpp"

namespace mimic {

struct GroundFit {
  Vec3 up = Vec3(0, -1, 0);         // the floor's normal, in camera coordinates (x right, y down, z ahead)
  Mat3 world_from_camera = Mat3::Identity();  // rows: the world's X (the view along the floor), Y (left), Z (up)
  bool fitted = false;              // false: the camera was taken as level
  double pitch_deg = 0;             // the view against the horizontal; below it, negative
};

// Each frame's lowest point (along the level camera's up) is a contact candidate. Where they
// spread (std ≥ 0.15 m) in two directions, the floor is the plane through them, refitted twice
// without the points more than 3 cm above it (airborne frames); in one direction (a walk in a
// line), the floor contains that line and is otherwise level with the camera; in none, or tilted
// more than 45 degrees, the camera is taken as level.
GroundFit fit_ground(const std::vector<std::vector<Vec3>>& frames);

}  // namespace mimic
