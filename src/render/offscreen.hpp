#pragma once
// Offscreen rendering of a MuJoCo scene with MuJoCo's renderer in a headless EGL context (Mesa's
// surfaceless platform: no display, no GPU needed). Optionally draws a second state of the same
// model as a translucent "ghost" (the reference motion beside or over the simulated character).
#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.hpp"

struct mjModel_;
struct mjData_;

namespace mimic {

struct CameraSpec {
  Vec3 lookat = Vec3(0, 0, 0.9);
  double distance = 3.5;
  double azimuth = 90.0;    // degrees; 90 looks at the character's left side when it faces +X
  double elevation = -12.0;  // degrees
};

class OffscreenRenderer {
 public:
  // Throws Error when no headless GL context can be created (the message says why).
  OffscreenRenderer(const mjModel_* model, int width, int height);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  // Renders `data` (and `ghost`, translucent, if given) into `rgb` (width*height*3, top row first).
  void render(mjData_* data, const CameraSpec& cam, std::vector<std::uint8_t>& rgb, mjData_* ghost = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_, height_;
};

}  // namespace mimic
