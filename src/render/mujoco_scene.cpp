#include "render/mujoco_scene.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace mimic {

struct MujocoScene::Impl {
  const mjModel* model = nullptr;
  mjvScene scene;
  mjvOption option;
  mjvCamera camera;
  mjrContext gl;
  std::vector<std::uint8_t> flipped;
};

MujocoScene::MujocoScene(const mjModel* model, bool offscreen) : impl_(new Impl) {
  Impl& s = *impl_;
  s.model = model;
  mjv_defaultScene(&s.scene);
  mjv_defaultOption(&s.option);
  mjv_defaultCamera(&s.camera);
  mjr_defaultContext(&s.gl);
  mjv_makeScene(model, &s.scene, 4000);
  mjr_makeContext(model, &s.gl, mjFONTSCALE_100);
  mjr_setBuffer(offscreen ? mjFB_OFFSCREEN : mjFB_WINDOW, &s.gl);
}

MujocoScene::~MujocoScene() {
  mjr_freeContext(&impl_->gl);
  mjv_freeScene(&impl_->scene);
  delete impl_;
}

int MujocoScene::offscreen_width() const { return impl_->gl.offWidth; }
int MujocoScene::offscreen_height() const { return impl_->gl.offHeight; }

void MujocoScene::draw(mjData* data, const CameraSpec& cam, int width, int height, mjData* ghost, const Overlay& overlay) {
  Impl& s = *impl_;
  if (cam.model_camera >= 0) {
    if (cam.model_camera >= s.model->ncam)
      throw Error("camera " + std::to_string(cam.model_camera) + " asked for: the model has " + std::to_string(s.model->ncam) + " cameras");
    s.camera.type = mjCAMERA_FIXED;
    s.camera.fixedcamid = cam.model_camera;
  } else {
    s.camera.type = mjCAMERA_FREE;
    for (int k = 0; k < 3; ++k) s.camera.lookat[k] = cam.lookat[k];
    s.camera.distance = cam.distance;
    s.camera.azimuth = cam.azimuth;
    s.camera.elevation = cam.elevation;
  }
  mjv_updateScene(s.model, data, &s.option, nullptr, &s.camera, mjCAT_ALL, &s.scene);
  if (ghost) {
    // The ghost's bodies (not the static floor), translucent and tinted.
    const int first = s.scene.ngeom;
    mjv_addGeoms(s.model, ghost, &s.option, nullptr, mjCAT_DYNAMIC, &s.scene);
    for (int g = first; g < s.scene.ngeom; ++g) {
      float* c = s.scene.geoms[g].rgba;
      c[0] = 0.95f, c[1] = 0.55f, c[2] = 0.25f, c[3] = 0.35f;
    }
  }
  const mjrRect viewport{0, 0, width, height};
  mjr_render(viewport, &s.scene, &s.gl);
  if (!overlay.left.empty() || !overlay.right.empty())
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, viewport, overlay.left.c_str(), overlay.right.empty() ? nullptr : overlay.right.c_str(), &s.gl);
}

void MujocoScene::read(int width, int height, std::vector<std::uint8_t>& rgb) {
  Impl& s = *impl_;
  const auto row = static_cast<std::size_t>(width) * 3;
  rgb.resize(row * static_cast<std::size_t>(height));
  s.flipped.resize(rgb.size());
  mjr_readPixels(s.flipped.data(), nullptr, mjrRect{0, 0, width, height}, &s.gl);
  for (int y = 0; y < height; ++y)  // OpenGL's rows start at the bottom
    std::copy_n(s.flipped.data() + static_cast<std::size_t>(height - 1 - y) * row, row, rgb.data() + static_cast<std::size_t>(y) * row);
}

}  // namespace mimic
