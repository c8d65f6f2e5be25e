#include "render/window.hpp"

#include <GLFW/glfw3.h>

#include <cstdlib>

#include "core/error.hpp"

namespace mimic {

namespace {

std::string glfw_error() {
  const char* what = nullptr;
  const int code = glfwGetError(&what);
  return code == GLFW_NO_ERROR ? std::string("no error reported") : std::string(what ? what : "unknown error");
}

std::string key_name(int key) {
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return std::string(1, static_cast<char>('0' + (key - GLFW_KEY_0)));
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, static_cast<char>('a' + (key - GLFW_KEY_A)));
  switch (key) {
    case GLFW_KEY_SPACE: return "space";
    case GLFW_KEY_ESCAPE: return "escape";
    case GLFW_KEY_LEFT: return "left";
    case GLFW_KEY_RIGHT: return "right";
    case GLFW_KEY_UP: return "up";
    case GLFW_KEY_DOWN: return "down";
    default: return "";
  }
}

}  // namespace

struct Window::Impl {
  GLFWwindow* window = nullptr;
  std::unique_ptr<MujocoScene> scene;
  std::vector<std::string> keys;
  bool escaped = false;

  static void on_key(GLFWwindow* w, int key, int /*scancode*/, int action, int /*mods*/) {
    auto* self = static_cast<Impl*>(glfwGetWindowUserPointer(w));
    const std::string name = key_name(key);
    const bool arrow = name == "left" || name == "right" || name == "up" || name == "down";
    if (name.empty() || !(action == GLFW_PRESS || (arrow && action == GLFW_REPEAT))) return;
    if (name == "escape") self->escaped = true;
    self->keys.push_back(name);
  }
};

namespace {

void init_glfw() {
  if (glfwInit()) return;
  const char* display = std::getenv("DISPLAY");
  throw Error(std::string("cannot open a window: ") + glfw_error() +
              (display && *display ? "" : " (DISPLAY is not set: run with --headless, or under xvfb-run)"));
}

}  // namespace

void Window::check_display() {
  init_glfw();
  glfwTerminate();
}

Window::Window(const mjModel_* model, int width, int height, const std::string& title) : impl_(std::make_unique<Impl>()) {
  if (width < 16 || height < 16 || width > 8192 || height > 8192) throw Error("window size must be 16..8192 pixels");
  init_glfw();
  glfwWindowHint(GLFW_SAMPLES, 4);
  glfwWindowHint(GLFW_VISIBLE, GLFW_TRUE);
  impl_->window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!impl_->window) {
    const std::string why = glfw_error();
    glfwTerminate();
    throw Error("cannot open a window: " + why);
  }
  glfwMakeContextCurrent(impl_->window);
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(impl_->window, impl_.get());
  glfwSetKeyCallback(impl_->window, &Impl::on_key);
  impl_->scene = std::make_unique<MujocoScene>(model, false);
}

Window::~Window() {
  if (impl_->window) {
    glfwMakeContextCurrent(impl_->window);
    impl_->scene.reset();
    glfwDestroyWindow(impl_->window);
    glfwTerminate();
  }
}

std::vector<std::string> Window::poll() {
  glfwPollEvents();
  std::vector<std::string> out;
  out.swap(impl_->keys);
  return out;
}

bool Window::closed() const { return impl_->escaped || glfwWindowShouldClose(impl_->window); }

int Window::framebuffer_width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(impl_->window, &w, &h);
  return w;
}

int Window::framebuffer_height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(impl_->window, &w, &h);
  return h;
}

void Window::draw(mjData_* data, const CameraSpec& cam, const Overlay& overlay, std::vector<std::uint8_t>* rgb) {
  glfwMakeContextCurrent(impl_->window);
  const int w = framebuffer_width(), h = framebuffer_height();
  impl_->scene->draw(data, cam, w, h, nullptr, overlay);
  if (rgb) impl_->scene->read(w, h, *rgb);
  glfwSwapBuffers(impl_->window);
}

}  // namespace mimic
