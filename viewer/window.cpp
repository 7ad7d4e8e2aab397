// SPDX-License-Identifier: MIT
#include "window.hpp"

#include <epoxy/egl.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <string>
#include <vector>

#include "runnel/core/error.hpp"
#include "viewer.hpp"

namespace runnel::viewer {
namespace {

void on_key(GLFWwindow*, int key, int, int action, int mods) {
  if (action == GLFW_PRESS) key_presses().push_back(key | ((mods & GLFW_MOD_CONTROL) ? kCtrl : 0));
}

bool has_extension(const char* list, const std::string& name) {
  const std::string all = list ? std::string(" ") + list + " " : "";
  return all.find(" " + name + " ") != std::string::npos;
}

// A display with no window system: the first EGL device (a GPU on a server, Mesa's software
// device here), else Mesa's surfaceless platform, else the default display.
EGLDisplay headless_display() {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (has_extension(client, "EGL_EXT_platform_device") &&
      has_extension(client, "EGL_EXT_device_enumeration")) {
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (eglQueryDevicesEXT(8, devices, &count) && count > 0) {
      for (EGLint k = 0; k < count; ++k) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[k], nullptr);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
      }
    }
  }
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) return d;
  throw runtime_error(
      "--headless: no EGL display (is libEGL with a GPU driver or Mesa installed?)");
}

}  // namespace

Window::Window(const ViewerOptions& options) : width_(options.width), height_(options.height) {
  if (options.headless)
    open_egl(options);
  else
    open_glfw(options);
  last_frame_ = opened_;
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini litter in the working folder
  if (glfw_) ImGui_ImplGlfw_InitForOpenGL(glfw_, true);
  ImGui_ImplOpenGL3_Init("#version 330");
}

Window::~Window() {
  ImGui_ImplOpenGL3_Shutdown();
  if (glfw_) ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  if (glfw_) {
    glfwDestroyWindow(glfw_);
    glfwTerminate();
  } else {
    eglMakeCurrent(egl_display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroySurface(egl_display_, egl_surface_);
    eglDestroyContext(egl_display_, egl_context_);
    eglTerminate(egl_display_);
  }
}

void Window::open_glfw(const ViewerOptions& options) {
  if (!glfwInit())
    throw runtime_error(
        "cannot initialise GLFW (is there a display? set DISPLAY, run under Xvfb, or use "
        "--headless)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfw_ = glfwCreateWindow(options.width, options.height, "runnel-viewer", nullptr, nullptr);
  if (!glfw_) {
    glfwTerminate();
    throw runtime_error("cannot open an OpenGL 3.3 core window");
  }
  glfwMakeContextCurrent(glfw_);
  glfwSwapInterval(0);
  glfwSetKeyCallback(glfw_, on_key);  // before ImGui installs its own, which calls it
}

// An OpenGL 3.3 core context on a pbuffer of the window's size: the same default framebuffer
// (GL_BACK) the windowed viewer draws to and reads its pictures from.
void Window::open_egl(const ViewerOptions& options) {
  EGLDisplay display = headless_display();
  egl_display_ = display;
  if (!eglBindAPI(EGL_OPENGL_API)) throw runtime_error("--headless: EGL has no desktop OpenGL");
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                      EGL_PBUFFER_BIT,
                                      EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT,
                                      EGL_RED_SIZE,
                                      8,
                                      EGL_GREEN_SIZE,
                                      8,
                                      EGL_BLUE_SIZE,
                                      8,
                                      EGL_DEPTH_SIZE,
                                      24,
                                      EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &configs) || configs < 1)
    throw runtime_error("--headless: no EGL configuration with an RGB8 pbuffer and a depth buffer");
  const EGLint surface_attributes[] = {EGL_WIDTH, options.width, EGL_HEIGHT, options.height,
                                       EGL_NONE};
  egl_surface_ = eglCreatePbufferSurface(display, config, surface_attributes);
  if (egl_surface_ == EGL_NO_SURFACE)
    throw runtime_error("--headless: cannot create a " + std::to_string(options.width) + "x" +
                        std::to_string(options.height) + " EGL pbuffer");
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                       3,
                                       EGL_CONTEXT_MINOR_VERSION,
                                       3,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  egl_context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
  if (egl_context_ == EGL_NO_CONTEXT)
    throw runtime_error("--headless: cannot create an OpenGL 3.3 core context through EGL");
  if (!eglMakeCurrent(display, egl_surface_, egl_surface_, egl_context_))
    throw runtime_error("--headless: cannot make the EGL context current");
}

bool Window::closing() const {
  return glfw_ ? glfwWindowShouldClose(glfw_) != 0 : closing_;
}

void Window::close() {
  if (glfw_)
    glfwSetWindowShouldClose(glfw_, 1);
  else
    closing_ = true;
}

void Window::poll_events() {
  if (glfw_) glfwPollEvents();
}

void Window::framebuffer_size(int& width, int& height) const {
  if (glfw_) {
    glfwGetFramebufferSize(glfw_, &width, &height);
  } else {
    width = width_;
    height = height_;
  }
}

void Window::window_size(int& width, int& height) const {
  if (glfw_) {
    glfwGetWindowSize(glfw_, &width, &height);
  } else {
    width = width_;
    height = height_;
  }
}

void Window::cursor(double& x, double& y) const {
  x = y = 0;
  if (glfw_) glfwGetCursorPos(glfw_, &x, &y);
}

bool Window::button_down(int glfw_button) const {
  return glfw_ && glfwGetMouseButton(glfw_, glfw_button) == GLFW_PRESS;
}

void Window::new_imgui_frame() {
  ImGui_ImplOpenGL3_NewFrame();
  if (glfw_) {
    ImGui_ImplGlfw_NewFrame();
    return;
  }
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(width_), static_cast<float>(height_));
  const auto now = std::chrono::steady_clock::now();
  io.DeltaTime = std::max(1e-4f, std::chrono::duration<float>(now - last_frame_).count());
  last_frame_ = now;
}

void Window::present() {
  if (glfw_) glfwSwapBuffers(glfw_);
}

double Window::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - opened_).count();
}

}  // namespace runnel::viewer
