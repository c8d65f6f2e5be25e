#include "render/offscreen.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <mujoco/mujoco.h>

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace mimic {
namespace {

std::string egl_error(const char* what) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s (EGL error 0x%x)", what, static_cast<unsigned>(eglGetError()));
  return std::string("no headless GL context: ") + buf;
}

}  // namespace

struct OffscreenRenderer::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  const mjModel* model = nullptr;
  mjvScene scene;
  mjvOption option;
  mjvCamera camera;
  mjrContext gl;
  bool scene_made = false, gl_made = false;

  ~Impl() {
    if (gl_made) mjr_freeContext(&gl);
    if (scene_made) mjv_freeScene(&scene);
    if (context != EGL_NO_CONTEXT) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
    // No eglTerminate: the display is shared by every renderer in the process.
  }
};

OffscreenRenderer::OffscreenRenderer(const mjModel* model, int width, int height)
    : impl_(std::make_unique<Impl>()), width_(width), height_(height) {
  if (width < 16 || height < 16 || width > 4096 || height > 4096) throw Error("render size must be 16..4096 pixels");
  Impl& s = *impl_;
  s.model = model;
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_display) s.display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (s.display == EGL_NO_DISPLAY) s.display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  EGLint major = 0, minor = 0;
  if (s.display == EGL_NO_DISPLAY || !eglInitialize(s.display, &major, &minor)) throw Error(egl_error("eglInitialize failed"));
  const EGLint attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_RED_SIZE, 8,
                            EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_NONE};
  EGLConfig config;
  EGLint count = 0;
  if (!eglChooseConfig(s.display, attribs, &config, 1, &count) || count < 1) throw Error(egl_error("no suitable EGL config"));
  if (!eglBindAPI(EGL_OPENGL_API)) throw Error(egl_error("desktop OpenGL unavailable"));
  s.context = eglCreateContext(s.display, config, EGL_NO_CONTEXT, nullptr);
  if (s.context == EGL_NO_CONTEXT) throw Error(egl_error("eglCreateContext failed"));
  if (!eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context)) throw Error(egl_error("eglMakeCurrent failed"));
  mjv_defaultScene(&s.scene);
  mjv_defaultOption(&s.option);
  mjv_defaultCamera(&s.camera);
  mjr_defaultContext(&s.gl);
  mjv_makeScene(model, &s.scene, 4000);
  s.scene_made = true;
  mjr_makeContext(model, &s.gl, mjFONTSCALE_100);
  s.gl_made = true;
  if (s.gl.offWidth < width || s.gl.offHeight < height)
    throw Error("render size " + std::to_string(width) + "x" + std::to_string(height) + " exceeds the model's offscreen buffer " +
                std::to_string(s.gl.offWidth) + "x" + std::to_string(s.gl.offHeight));
  mjr_setBuffer(mjFB_OFFSCREEN, &s.gl);
}

OffscreenRenderer::~OffscreenRenderer() = default;

void OffscreenRenderer::render(mjData* data, const CameraSpec& cam, std::vector<std::uint8_t>& rgb, mjData* ghost) {
  Impl& s = *impl_;
  eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context);
  s.camera.type = mjCAMERA_FREE;
  for (int k = 0; k < 3; ++k) s.camera.lookat[k] = cam.lookat[k];
  s.camera.distance = cam.distance;
  s.camera.azimuth = cam.azimuth;
  s.camera.elevation = cam.elevation;
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
  const mjrRect viewport{0, 0, width_, height_};
  mjr_render(viewport, &s.scene, &s.gl);
  const auto row = static_cast<std::size_t>(width_) * 3;
  rgb.resize(row * static_cast<std::size_t>(height_));
  std::vector<std::uint8_t> flipped(rgb.size());
  mjr_readPixels(flipped.data(), nullptr, viewport, &s.gl);
  for (int y = 0; y < height_; ++y)  // OpenGL's rows start at the bottom
    std::copy_n(flipped.data() + static_cast<std::size_t>(height_ - 1 - y) * row, row, rgb.data() + static_cast<std::size_t>(y) * row);
}

}  // namespace mimic
