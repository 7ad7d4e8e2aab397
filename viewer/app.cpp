// SPDX-License-Identifier: MIT
// runnel-viewer: the simulation core of `runnel run` in a GLFW window, with rain painted by mouse.
#include "app.hpp"

#include <epoxy/gl.h>
// GLFW after the GL loader, which provides the GL declarations.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <map>

#include "camera.hpp"
#include "renderers.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/scenario.hpp"
#include "runnel/io/images.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/sph_model.hpp"
#include "runnel/terrain/ray_pick.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace runnel::viewer {
namespace {

using Clock = std::chrono::steady_clock;

struct Brush {
  bool over_terrain = false;
  double x = 0, z = 0;
  double radius = 20;    // m
  double intensity = 0;  // mm/h over the brush disc
};

class Viewer {
 public:
  Viewer(const ViewerOptions& options, GLFWwindow* window)
      : options_(options), window_(window), compute_(options.device) {
    load();
  }

  int loop();

 private:
  void load();
  void reset();
  void save_checkpoint();
  void load_checkpoint(const std::string& path);
  void frame_camera();
  void screenshot(const std::string& path);
  void handle_input();
  void update_rain();
  void advance();
  void upload();
  void draw_panel();
  void print_stats(long long frame, double fps);
  // A key that went down since the last frame.
  bool pressed(int key) {
    const bool down = glfwGetKey(window_, key) == GLFW_PRESS;
    const bool edge = down && !keys_down_[key];
    keys_down_[key] = down;
    return edge;
  }
  std::map<int, bool> keys_down_;

  ViewerOptions options_;
  GLFWwindow* window_;
  ComputeContext compute_;
  std::string input_;
  std::unique_ptr<CheckpointData> start_checkpoint_;
  Parameters params_;
  Heightmap start_terrain_;
  std::unique_ptr<SphModel> sim_;  // the SPH model, driven through Model
  RainSettings global_rain_;
  std::unique_ptr<TerrainRenderer> terrain_;
  std::unique_ptr<ParticleRenderer> particles_;
  OrbitCamera camera_;
  Brush brush_;
  bool playing_ = true, step_once_ = false, global_rain_on_ = true, painting_ = false,
       help_ = false;
  TerrainOverlay overlay_ = TerrainOverlay::kNone;
  ParticleColour particle_colour_ = ParticleColour::kSediment;
  float min_height_ = 0, max_height_ = 1;
  double steps_per_second_ = 0;
  double last_x_ = 0, last_y_ = 0;
  MassBalance balance_;
  std::string message_;
  char load_path_[512] = "runnel-out/final.h5";
};

void Viewer::load() {
  const std::string& in = options_.input;
  if (!in.empty() && std::filesystem::path(in).extension() == ".h5") {
    start_checkpoint_ = std::make_unique<CheckpointData>(read_checkpoint(in));
    params_ = parse_scenario(start_checkpoint_->parameters_toml, "checkpoint parameters");
  } else {
    params_ = in.empty() ? Parameters() : load_scenario(in);
    start_terrain_ = load_terrain(params_);
  }
  global_rain_on_ = options_.rain;
  overlay_ = static_cast<TerrainOverlay>(options_.overlay);
  reset();
}

void Viewer::reset() {
  if (start_checkpoint_) {  // the model restores itself from its checkpoint
    sim_ = std::make_unique<SphModel>(compute_, params_, start_checkpoint_->initial_terrain());
    sim_->restore(*start_checkpoint_);
  } else {
    sim_ = std::make_unique<SphModel>(compute_, params_, start_terrain_);
  }
  global_rain_ = sim_->rain();
  const Heightmap& t = sim_->initial_terrain();
  min_height_ = t.min_height();
  max_height_ = std::max(t.max_height(), min_height_ + 1e-3f);
  const float extent = static_cast<float>(std::max(t.nx - 1, t.ny - 1) * t.cell);
  frame_camera();
  brush_.radius = 0.05 * extent;
  // A brush intensity that rains about 300 particles per second at the starting radius.
  const double dx = sim_->particle_spacing();
  brush_.intensity = 300.0 * dx * dx * dx / (M_PI * brush_.radius * brush_.radius) * 3.6e6;
  terrain_ = std::make_unique<TerrainRenderer>(t);
  particles_ = std::make_unique<ParticleRenderer>();
  upload();
}

void Viewer::frame_camera() {
  const Heightmap& t = sim_->initial_terrain();
  const float extent = static_cast<float>(std::max(t.nx - 1, t.ny - 1) * t.cell);
  camera_.frame(glm::vec3(0.5f * (t.nx - 1) * t.cell, 0.5f * (min_height_ + max_height_),
                          0.5f * (t.ny - 1) * t.cell),
                extent);
}

// Replaces the running simulation by a checkpoint's; a bad file leaves the current one running.
void Viewer::load_checkpoint(const std::string& path) {
  try {
    auto data = std::make_unique<CheckpointData>(read_checkpoint(path));
    start_checkpoint_ = std::move(data);
    params_ = parse_scenario(start_checkpoint_->parameters_toml, "checkpoint parameters");
    reset();
    message_ = "loaded " + path;
  } catch (const Error& e) {
    message_ = e.what();
  }
}

void Viewer::save_checkpoint() {
  const std::string path = "runnel-viewer-step" + std::to_string(sim_->steps()) + ".h5";
  write_checkpoint(path, sim_->checkpoint());
  message_ = "saved " + path;
}

void Viewer::screenshot(const std::string& path) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * h * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  RgbImage image(w, h);
  for (int y = 0; y < h; ++y) {  // GL rows start at the bottom
    std::copy_n(pixels.data() + static_cast<std::size_t>(h - 1 - y) * w * 3,
                static_cast<std::size_t>(w) * 3,
                image.rgb.data() + static_cast<std::size_t>(y) * w * 3);
  }
  write_png_rgb(path, image);
  message_ = "screenshot " + path;
}

void Viewer::handle_input() {
  ImGuiIO& io = ImGui::GetIO();
  double x = 0, y = 0;
  glfwGetCursorPos(window_, &x, &y);
  const double dx = x - last_x_, dy = y - last_y_;
  last_x_ = x;
  last_y_ = y;
  int w = 0, h = 0;
  glfwGetWindowSize(window_, &w, &h);
  if (!io.WantCaptureMouse) {
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
      camera_.orbit(static_cast<float>(dx), static_cast<float>(dy));
    if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) {
      camera_.pan(static_cast<float>(dx), static_cast<float>(dy), static_cast<float>(h));
    }
    if (io.MouseWheel != 0.0f) {
      if (io.KeyCtrl || io.KeyShift)
        brush_.radius = std::max(0.5, brush_.radius * std::pow(1.15, io.MouseWheel));
      else
        camera_.zoom(io.MouseWheel);
    }
  }
  // The cursor ray against the terrain: where the brush is.
  glm::dvec3 origin, direction;
  camera_.ray(x, y, std::max(w, 1), std::max(h, 1), origin, direction);
  const double o[3] = {origin.x, origin.y, origin.z},
               d[3] = {direction.x, direction.y, direction.z};
  const auto hit = pick_terrain(sim_->initial_terrain(), o, d);
  brush_.over_terrain = hit.has_value() && !io.WantCaptureMouse;
  if (hit) {
    brush_.x = hit->x;
    brush_.z = hit->z;
  }
  painting_ =
      brush_.over_terrain && glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  if (!io.WantCaptureKeyboard) {
    if (pressed(GLFW_KEY_SPACE)) playing_ = !playing_;
    if (pressed(GLFW_KEY_N)) step_once_ = true;
    if (pressed(GLFW_KEY_R)) reset();
    if (pressed(GLFW_KEY_S)) save_checkpoint();
    if (pressed(GLFW_KEY_P)) screenshot("runnel-viewer-" + std::to_string(sim_->steps()) + ".png");
    if (pressed(GLFW_KEY_H)) help_ = !help_;
    if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window_, 1);
  }
}

// Painting replaces the rain region by the brush disc; the rate is the brush's intensity over its
// area, so the water painted depends neither on mouse speed nor on the frame rate.
void Viewer::update_rain() {
  RainSettings rain = sim_->rain();
  const double dx = sim_->particle_spacing();
  if (painting_) {
    rain.rain_on_disc(brush_.x, brush_.z, brush_.radius, brush_.intensity, dx);
  } else {
    const auto carry_budget = rain.max_particles;
    rain = global_rain_;
    rain.max_particles = carry_budget;
    rain.enabled = global_rain_on_;
  }
  sim_->set_rain(rain);
}

void Viewer::advance() {
  if (!playing_ && !step_once_) {
    steps_per_second_ = 0;
    return;
  }
  // As many steps as fit in about 25 ms, so the window stays responsive at any particle count.
  const auto start = Clock::now();
  int steps = 0;
  do {
    sim_->step();
    ++steps;
  } while (!step_once_ && Clock::now() - start < std::chrono::milliseconds(25) && steps < 200);
  step_once_ = false;
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  steps_per_second_ = steps / std::max(seconds, 1e-6);
}

void Viewer::upload() {
  const Heightmap t = sim_->terrain();
  const std::size_t n = t.size();
  terrain_->update(t.h, sim_->terrain_normals());
  const HostParticles p = sim_->particles();
  std::vector<float> xyzv(4 * p.size());
  const double q = sim_->volume_quantum(), volume = std::pow(sim_->particle_spacing(), 3);
  for (std::size_t i = 0; i < p.size(); ++i) {
    xyzv[4 * i] = p.f[kX][i];
    xyzv[4 * i + 1] = p.f[kY][i];
    xyzv[4 * i + 2] = p.f[kZ][i];
    float value = 0;
    if (particle_colour_ == ParticleColour::kSediment) {
      value = static_cast<float>(
          std::min(1.0, 20.0 * p.sediment[i] * q / volume));  // 5 % load is full colour
    } else {
      value = std::min(1.0f, std::sqrt(p.f[kVx][i] * p.f[kVx][i] + p.f[kVy][i] * p.f[kVy][i] +
                                       p.f[kVz][i] * p.f[kVz][i]) /
                                 15.0f);
    }
    xyzv[4 * i + 3] = value;
  }
  particles_->update(xyzv);
  // Water depth and flow speed per vertex: each particle's volume spread over its nearest vertex.
  const int nx = t.nx, ny = t.ny;
  const float cell = static_cast<float>(t.cell);
  std::vector<float> water(2 * n, 0.0f);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int a = std::clamp(static_cast<int>(std::lround(p.f[kX][i] / cell)), 0, nx - 1);
    const int b = std::clamp(static_cast<int>(std::lround(p.f[kZ][i] / cell)), 0, ny - 1);
    const std::size_t k = static_cast<std::size_t>(b) * nx + a;
    water[2 * k] += static_cast<float>(volume / (cell * cell));
    water[2 * k + 1] += std::sqrt(p.f[kVx][i] * p.f[kVx][i] + p.f[kVy][i] * p.f[kVy][i] +
                                  p.f[kVz][i] * p.f[kVz][i]);
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (water[2 * k] > 0)
      water[2 * k + 1] /= static_cast<float>(water[2 * k] * cell * cell / volume);
  }
  terrain_->update_water(water);
  terrain_->set_depth_scale(static_cast<float>(2.0 * sim_->particle_spacing()));
}

void Viewer::draw_panel() {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("runnel");
  ImGui::Text("model: sph (SPH rain erosion)");
  if (ImGui::Button(playing_ ? "Pause" : "Play")) playing_ = !playing_;
  ImGui::SameLine();
  if (ImGui::Button("Step")) step_once_ = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset")) reset();
  ImGui::SameLine();
  if (ImGui::Button("Reset view")) frame_camera();
  if (ImGui::Button("Save checkpoint")) save_checkpoint();
  ImGui::SameLine();
  if (ImGui::Button("Screenshot"))
    screenshot("runnel-viewer-" + std::to_string(sim_->steps()) + ".png");
  ImGui::InputText("##checkpoint", load_path_, sizeof load_path_);
  ImGui::SameLine();
  if (ImGui::Button("Load checkpoint")) load_checkpoint(load_path_);
  ImGui::Separator();
  ImGui::Checkbox("global rain", &global_rain_on_);
  float radius = static_cast<float>(brush_.radius),
        intensity = static_cast<float>(brush_.intensity);
  if (ImGui::SliderFloat("brush radius (m)", &radius, 0.5f, 500.0f, "%.1f",
                         ImGuiSliderFlags_Logarithmic))
    brush_.radius = radius;
  if (ImGui::SliderFloat("brush rain (mm/h)", &intensity, 1e3f, 1e9f, "%.3g",
                         ImGuiSliderFlags_Logarithmic)) {
    brush_.intensity = intensity;
  }
  int overlay = static_cast<int>(overlay_), colour = static_cast<int>(particle_colour_);
  ImGui::Combo("terrain overlay", &overlay,
               "none\0erosion / deposition\0water depth\0flow speed\0");
  ImGui::Combo("water colour", &colour, "sediment load\0flow speed\0");
  overlay_ = static_cast<TerrainOverlay>(overlay);
  particle_colour_ = static_cast<ParticleColour>(colour);
  ImGui::Separator();
  ImGui::Text("particles: %zu", sim_->particle_count());
  ImGui::Text("steps/s: %.0f   step %llu", steps_per_second_,
              static_cast<unsigned long long>(sim_->steps()));
  ImGui::Text("simulated time: %.2f s", sim_->time());
  ImGui::Text("eroded %.4g m3, deposited %.4g m3", balance_.eroded, balance_.deposited);
  ImGui::Text("mass balance %.2e m3 (rel %.1e)", balance_.residual, balance_.relative);
  ImGui::Text("framerate: %.1f fps", ImGui::GetIO().Framerate);
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
  if (ImGui::CollapsingHeader("parameters")) {
    for (auto& [key, value] : sim_->parameters().values()) {
      ImGui::Text("%s = %s", key.c_str(), Parameters::to_text(value).c_str());
    }
  }
  ImGui::End();
  if (help_) {
    ImGui::Begin("help", &help_);
    ImGui::Text("left drag: paint rain   right drag: orbit   middle drag: pan");
    ImGui::Text("wheel: zoom   ctrl/shift + wheel: brush radius");
    ImGui::Text("space: play/pause   N: step   R: reset   S: save checkpoint");
    ImGui::Text("P: screenshot   H: this help   Esc: quit");
    ImGui::End();
  }
}

void Viewer::print_stats(long long frame, double fps) {
  std::printf("%s\n", JsonObject()
                          .add("frame", frame)
                          .add("particles", static_cast<long long>(sim_->particle_count()))
                          .add("steps", static_cast<long long>(sim_->steps()))
                          .add("steps_per_second", steps_per_second_)
                          .add("eroded_volume", balance_.eroded)
                          .add("mass_balance_abs", balance_.residual)
                          .add("painting", painting_)
                          .add("fps", fps)
                          .str()
                          .c_str());
  std::fflush(stdout);
}

int Viewer::loop() {
  long long frame = 0;
  auto fps_start = Clock::now();
  long long fps_frames = 0;
  double fps = 0;
  while (!glfwWindowShouldClose(window_)) {
    glfwPollEvents();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    handle_input();
    update_rain();
    advance();
    upload();
    if (frame % 10 == 0) balance_ = sim_->mass_balance();

    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    glViewport(0, 0, w, h);
    glClearColor(0.55f, 0.68f, 0.82f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    const glm::mat4 vp =
        camera_.projection(static_cast<float>(w) / std::max(h, 1)) * camera_.view();
    const float scale = static_cast<float>(std::max(1e-3, 0.02 * (max_height_ - min_height_)));
    terrain_->draw(vp, min_height_, max_height_, overlay_, scale,
                   glm::vec3(brush_.x, brush_.z, brush_.radius), brush_.over_terrain);
    particles_->draw(vp, static_cast<float>(sim_->particle_spacing()), static_cast<float>(h),
                     particle_colour_);
    draw_panel();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    ++frame;
    ++fps_frames;
    const double since = std::chrono::duration<double>(Clock::now() - fps_start).count();
    if (since >= 0.5) {
      fps = fps_frames / since;
      fps_frames = 0;
      fps_start = Clock::now();
    }
    if (options_.stats_every > 0 && frame % options_.stats_every == 0) print_stats(frame, fps);
    const bool last = options_.frames > 0 && frame >= options_.frames;
    if (last && !options_.screenshot.empty()) screenshot(options_.screenshot);
    glfwSwapBuffers(window_);
    if (last) break;
  }
  return 0;
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
