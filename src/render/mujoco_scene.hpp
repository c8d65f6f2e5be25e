#pragma once
// MuJoCo's abstract scene and its OpenGL resources for one model, drawn into whatever framebuffer
// the current GL context has (an EGL pbuffer: offscreen.hpp; a GLFW window: window.hpp).
#include <cstdint>
#include <string>
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
  int model_camera = -1;     // >= 0: the model's own camera of that index (an MJCF <camera>); the rest is then unused
};

// Text drawn over a picture: lines on the left and the right of its top (MuJoCo's overlay).
struct Overlay {
  std::string left, right;
};

class MujocoScene {
 public:
  // A GL context must be current. `offscreen`: draw into MuJoCo's offscreen buffer (whose size
  // the model's <visual><global offwidth/offheight> sets) instead of the window's.
  MujocoScene(const mjModel_* model, bool offscreen);
  ~MujocoScene();
  MujocoScene(const MujocoScene&) = delete;
  MujocoScene& operator=(const MujocoScene&) = delete;

  int offscreen_width() const;
  int offscreen_height() const;
  // Draws `data` (and `ghost`, translucent, if given) seen from `cam` into the width x height
  // viewport, with `overlay`'s text.
  void draw(mjData_* data, const CameraSpec& cam, int width, int height, mjData_* ghost = nullptr, const Overlay& overlay = {});
  // The viewport's pixels as RGB, top row first.
  void read(int width, int height, std::vector<std::uint8_t>& rgb);

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace mimic
