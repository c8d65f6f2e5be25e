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
  std::unique_ptr<MujocoScene> scene;

  ~Impl() {
    if (context != EGL_NO_CONTEXT && scene) eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context);
    scene.reset();  // (its GL resources, while the context is current)
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
  s.scene = std::make_unique<MujocoScene>(model, true);
  if (s.scene->offscreen_width() < width || s.scene->offscreen_height() < height)
    throw Error("render size " + std::to_string(width) + "x" + std::to_string(height) + " exceeds the model's offscreen buffer " +
                std::to_string(s.scene->offscreen_width()) + "x" + std::to_string(s.scene->offscreen_height()));
}

OffscreenRenderer::~OffscreenRenderer() = default;

void OffscreenRenderer::render(mjData* data, const CameraSpec& cam, std::vector<std::uint8_t>& rgb, mjData* ghost, const Overlay& overlay) {
  Impl& s = *impl_;
  eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context);
  s.scene->draw(data, cam, width_, height_, ghost, overlay);
  s.scene->read(width_, height_, rgb);
}

}  // namespace mimic
