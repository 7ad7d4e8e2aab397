// SPDX-License-Identifier: MIT
#pragma once
#include <epoxy/gl.h>
// GLFW after the GL loader, which provides the GL declarations.
#include <GLFW/glfw3.h>

#include <chrono>

#include "app.hpp"

namespace runnel::viewer {

// Where the viewer draws: a GLFW window on a display, or (--headless) an EGL context with no
// display at all, drawing into an off-screen surface of the window's size (a GPU server, CI): the
// same pictures, benchmarks and recordings, without mouse or keys. It owns the GL context and
// ImGui's platform side.
class Window {
 public:
  explicit Window(const ViewerOptions& options);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  bool headless() const { return glfw_ == nullptr; }
  GLFWwindow* glfw() const { return glfw_; }  // null when headless
  // What the GL reports itself to be (GL_RENDERER), and through what it was opened.
  const char* api() const { return headless() ? "egl" : "glfw"; }

  bool closing() const;
  void close();
  void poll_events();
  void framebuffer_size(int& width, int& height) const;
  void window_size(int& width, int& height) const;
  // The cursor in window coordinates and whether a mouse button is down; headless: none.
  void cursor(double& x, double& y) const;
  bool button_down(int glfw_button) const;
  // ImGui's frame start: its GLFW side, or the display's size and the clock by hand.
  void new_imgui_frame();
  // Shows the frame (a swap); headless: nothing, the surface is read as it is.
  void present();
  // Seconds since the window opened.
  double seconds() const;

 private:
  void open_glfw(const ViewerOptions& options);
  void open_egl(const ViewerOptions& options);
  GLFWwindow* glfw_ = nullptr;
  void* egl_display_ = nullptr;
  void* egl_context_ = nullptr;
  void* egl_surface_ = nullptr;
  int width_ = 0, height_ = 0;
  bool closing_ = false;
  std::chrono::steady_clock::time_point opened_ = std::chrono::steady_clock::now(), last_frame_;
};

}  // namespace runnel::viewer
