#pragma once
// A window on the screen showing a MuJoCo scene (GLFW and MuJoCo's renderer), with the keys the
// user presses: what `mimic play` draws into. Needs a display (an X server: under CI, Xvfb).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/mujoco_scene.hpp"

struct mjModel_;
struct mjData_;

namespace mimic {

class Window {
 public:
  // Throws Error when no window can be opened, saying why (no display: DISPLAY unset or the X
  // server unreachable).
  Window(const mjModel_* model, int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  // Throws the constructor's Error when no window could be opened (no display), before a program
  // spends time on what it would show.
  static void check_display();
  Window& operator=(const Window&) = delete;

  // Handles the window system's events; returns the keys pressed since the last call, by name:
  // "0".."9", "a".."z", "space", "escape", "left", "right", "up", "down" (held arrows repeat).
  std::vector<std::string> poll();
  bool closed() const;  // the user closed the window (or pressed escape)
  // Draws `data` seen from `cam` with `overlay`'s text and shows it; with `rgb`, also reads the
  // frame (framebuffer_width() x framebuffer_height(), RGB, top row first) before showing it.
  void draw(mjData_* data, const CameraSpec& cam, const Overlay& overlay, std::vector<std::uint8_t>* rgb = nullptr);
  int framebuffer_width() const;
  int framebuffer_height() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mimic
