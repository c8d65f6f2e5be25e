#pragma once
// Offscreen rendering of a MuJoCo scene with MuJoCo's renderer in a headless EGL context (Mesa's
// surfaceless platform: no display, no GPU needed). Optionally draws a second state of the same
// model as a translucent "ghost" (the reference motion beside or over the simulated character).
#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.hpp"
#include "render/mujoco_scene.hpp"

struct mjModel_;
struct mjData_;

namespace mimic {

// Where a following camera looks: the character's root smoothed over frames (a steady picture of
// a gait's sway), taken as it is at the first frame and at the first after restart(). A new
// episode puts the character back at its start; smoothing across that left the camera on empty
// floor for a second.
class CameraFollow {
 public:
  explicit CameraFollow(double keep = 0.9) : keep_(keep) {}
  Vec3 update(const Vec3& root) {
    at_ = fresh_ ? root : Vec3(keep_ * at_ + (1.0 - keep_) * root);
    fresh_ = false;
    return at_;
  }
  void restart() { fresh_ = true; }

 private:
  double keep_;
  Vec3 at_ = Vec3::Zero();
  bool fresh_ = true;
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
  // Renders `data` (and `ghost`, translucent, if given) into `rgb` (width*height*3, top row first),
  // with `overlay`'s text over it.
  void render(mjData_* data, const CameraSpec& cam, std::vector<std::uint8_t>& rgb, mjData_* ghost = nullptr, const Overlay& overlay = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_, height_;
};

}  // namespace mimic
