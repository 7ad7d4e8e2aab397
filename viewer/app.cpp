// SPDX-License-Identifier: MIT
// runnel-viewer's window: GLFW, the GL context, ImGui, and the viewer in it (viewer.hpp).
#include "app.hpp"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include "runnel/core/error.hpp"
#include "viewer.hpp"

namespace runnel::viewer {
namespace {

void on_key(GLFWwindow*, int key, int, int action, int mods) {
  if (action == GLFW_PRESS) key_presses().push_back(key | ((mods & GLFW_MOD_CONTROL) ? kCtrl : 0));
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
  if (!glfwInit())
    throw runtime_error(
        "cannot initialise GLFW (is there a display? set DISPLAY or run under Xvfb)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window =
      glfwCreateWindow(options.width, options.height, "runnel-viewer", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    throw runtime_error("cannot open an OpenGL 3.3 core window");
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(0);
  glfwSetKeyCallback(window, on_key);  // before ImGui installs its own, which calls it
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini litter in the working folder
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330");
  int code = 0;
  {
    Viewer viewer(options, window);
    code = viewer.loop();
  }
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace runnel::viewer
