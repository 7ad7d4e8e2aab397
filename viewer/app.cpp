// SPDX-License-Identifier: MIT
// runnel-viewer: any erosion model of runnel in a GLFW window, with rain painted by mouse. The
// window drives a Session (src/runnel/interactive), which runs the model and logs what the user
// does to it; this file turns input into session actions and the session into pictures.
#include "app.hpp"

#include <epoxy/gl.h>
// GLFW after the GL loader, which provides the GL declarations.
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <set>

#include "brush.hpp"
#include "camera.hpp"
#include "recorder.hpp"
#include "renderers.hpp"
#include "runnel/compute/context.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/scenario.hpp"
#include "runnel/interactive/session.hpp"
#include "runnel/io/json.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/terrain/ray_pick.hpp"
#include "runnel/terrain/terrain_normals.hpp"
#include "runnel/terrain/terrain_source.hpp"
#include "water_renderer.hpp"

namespace runnel::viewer {
namespace {

using Clock = std::chrono::steady_clock;

// Key presses since the viewer last took them (the GLFW key callback, which ImGui chains to).
// A press with ctrl held is the key plus kCtrl: the modifiers come with the event, since ctrl may
// be up again by the time the frame looks.
constexpr int kCtrl = 1 << 20;
std::vector<int> g_key_presses;
void on_key(GLFWwindow*, int key, int, int action, int mods) {
  if (action == GLFW_PRESS) g_key_presses.push_back(key | ((mods & GLFW_MOD_CONTROL) ? kCtrl : 0));
}

class Viewer {
 public:
  Viewer(const ViewerOptions& options, GLFWwindow* window)
      : options_(options), window_(window), compute_(options.device) {
    load();
  }

  int loop();

 private:
  void load();
  void on_new_model();
  void save_checkpoint();
  void frame_camera();
  void screenshot(const std::string& path);
  void toggle_recording();
  void handle_input();
  void update_rain();
  void advance();
  void advance_unguarded();
  void upload();
  // The terrain, the water and (when shown) the particles; the brush ring only on the screen, not
  // in screenshots and recordings.
  void render_scene(int width, int height, bool with_brush = false);
  void draw_panel();
  void print_stats(long long frame, double fps);
  void finish();
  double record_interval() const;
  // A key that went down since the last frame, from the key events: polling the key's state
  // misses a press and release that arrive together (a quick tap, xdotool key).
  bool pressed(int key) const { return presses_.count(key) > 0; }
  std::set<int> presses_;

  ViewerOptions options_;
  GLFWwindow* window_;
  ComputeContext compute_;
  std::unique_ptr<Session> session_;
  std::uint64_t shown_generation_ = 0;  // the session's model the renderers were built for
  std::unique_ptr<TerrainRenderer> terrain_;
  std::unique_ptr<WaterRenderer> water_;
  std::unique_ptr<ParticleRenderer> particles_;
  std::unique_ptr<FrameRecorder> recorder_;
  OrbitCamera camera_;
  Brush brush_;
  std::vector<RainDisc> sources_;
  // What the brush paints: rain, or the ground's erodibility mask (layered ground only).
  enum class BrushMode { kRain = 0, kFreeze = 1, kHarden = 2, kRestore = 3 };
  BrushMode brush_mode_ = BrushMode::kRain;
  RainDisc last_mask_disc_;
  bool playing_ = true, step_once_ = false, help_ = false, show_particles_ = false;
  bool mouse_down_ = false, failed_ = false;
  TerrainOverlay overlay_ = TerrainOverlay::kNone;
  ParticleColour particle_colour_ = ParticleColour::kSediment;
  float min_height_ = 0, max_height_ = 1;
  double steps_per_second_ = 0;
  double last_x_ = 0, last_y_ = 0;
  MassBalance balance_;
  double rain_volume_ = 0;
  std::string message_;
  std::vector<std::string> model_names_;
  // What the panel asked for, done at the next frame's start: a model replaced in the middle of
  // drawing the panel would leave it reading a model that is gone.
  std::vector<std::function<void()>> panel_actions_;
  void open(const std::string& path);
  char load_path_[512] = "runnel-out/final.h5";
};

void Viewer::load() {
  std::string input = options_.input;
  SessionLog replay;
  if (!options_.replay.empty()) {
    replay = read_session_log(options_.replay);
    if (input.empty()) input = replay.input;
    options_.rain = replay.global_rain;
  }
  if (!input.empty() && std::filesystem::path(input).extension() == ".h5") {
    session_ = std::make_unique<Session>(compute_, read_checkpoint(input), input, options_.rain);
  } else {
    Parameters params = input.empty() ? Parameters() : load_scenario(input);
    if (!options_.model.empty()) {
      model_entry(options_.model);  // an unknown name is refused with the list
      params.set("run.model", options_.model, "--model");
    }
    session_ =
        std::make_unique<Session>(compute_, params, load_terrain(params), input, options_.rain);
  }
  if (!options_.replay.empty()) session_->start_replay(replay);
  model_names_ = model_names();
  overlay_ = static_cast<TerrainOverlay>(options_.overlay);
  show_particles_ = options_.particles;
  playing_ = !options_.paused;
  on_new_model();
  brush_ = default_brush(session_->model().initial_terrain());
  frame_camera();
  if (!options_.record.empty()) toggle_recording();
}

// The renderers follow the model's initial terrain (the erosion overlay is measured from it).
void Viewer::on_new_model() {
  Model& model = session_->model();
  shown_generation_ = session_->model_generation();
  if (!model.ground()) brush_mode_ = BrushMode::kRain;
  failed_ = false;
  const Heightmap& t = model.initial_terrain();
  min_height_ = t.min_height();
  max_height_ = std::max(t.max_height(), min_height_ + 1e-3f);
  terrain_ = std::make_unique<TerrainRenderer>(t);
  water_ = std::make_unique<WaterRenderer>(t);
  particles_ = std::make_unique<ParticleRenderer>();
  upload();
}

// Another scenario or checkpoint, of any model; a bad file leaves the current session running.
void Viewer::open(const std::string& path) {
  try {
    if (std::filesystem::path(path).extension() == ".h5") {
      session_ =
          std::make_unique<Session>(compute_, read_checkpoint(path), path, session_->global_rain());
    } else {
      const Parameters params = load_scenario(path);
      session_ = std::make_unique<Session>(compute_, params, load_terrain(params), path,
                                           session_->global_rain());
    }
    sources_.clear();
    on_new_model();
    frame_camera();
    message_ = "opened " + path;
  } catch (const Error& e) {
    message_ = e.what();
  }
}

void Viewer::frame_camera() {
  const Heightmap& t = session_->model().initial_terrain();
  const float extent = static_cast<float>(std::max(t.nx - 1, t.ny - 1) * t.cell);
  camera_.frame(glm::vec3(0.5f * (t.nx - 1) * t.cell, 0.5f * (min_height_ + max_height_),
                          0.5f * (t.ny - 1) * t.cell),
                extent);
}

void Viewer::save_checkpoint() {
  Model& m = session_->model();
  const std::string path =
      "runnel-viewer-" + m.info().name + "-step" + std::to_string(m.steps()) + ".h5";
  write_checkpoint(path, m.checkpoint());
  message_ = "saved " + path;
}

// The scene without the panel, at screenshot_scale × the window, rendered offscreen.
void Viewer::screenshot(const std::string& path) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  const int scale = std::max(1, options_.screenshot_scale);
  try {
    OffscreenTarget target(w * scale, h * scale);
    target.bind();
    render_scene(target.width(), target.height());
    const RgbImage image = read_framebuffer(target.width(), target.height());
    OffscreenTarget::unbind();
    write_png_rgb(path, image);
    message_ = "screenshot " + path + " (" + std::to_string(target.width()) + "x" +
               std::to_string(target.height()) + ")";
  } catch (const Error& e) {
    OffscreenTarget::unbind();
    message_ = e.what();
  }
  glViewport(0, 0, w, h);
}

double Viewer::record_interval() const {
  if (options_.record_interval > 0) return options_.record_interval;
  return session_->model().info().clock == ModelClock::kSeconds ? 0.1 : 1.0;
}

void Viewer::toggle_recording() {
  if (recorder_) {
    message_ =
        "recorded " + std::to_string(recorder_->frames()) + " frames to " + recorder_->target();
    recorder_.reset();
    return;
  }
  const std::string path =
      options_.record.empty() ? "runnel-viewer-recording.mp4" : options_.record;
  recorder_ = std::make_unique<FrameRecorder>(path, options_.record_fps);
  message_ = "recording to " + recorder_->target();
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
  const auto hit = pick_terrain(session_->model().initial_terrain(), o, d);
  brush_.over_terrain = hit.has_value() && !io.WantCaptureMouse;
  if (hit) {
    brush_.x = hit->x;
    brush_.z = hit->z;
  }
  const bool down = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool painting_rain = brush_mode_ == BrushMode::kRain;
  const bool can_paint =
      !session_->replaying() &&
      (painting_rain ? session_->model().paints_rain() : session_->model().ground() != nullptr);
  if (down && !mouse_down_ && brush_.over_terrain && can_paint) session_->begin_stroke();
  if (down && !mouse_down_ && brush_.over_terrain && !can_paint && !session_->replaying()) {
    message_ = painting_rain ? "the " + session_->model().info().name + " model takes no rain"
                             : "no layered ground here: the scenario has no [[layers]] or masks";
  }
  if (!down && session_->painting() && !session_->replaying()) session_->end_stroke();
  mouse_down_ = down && (mouse_down_ || brush_.over_terrain);
  // A mask stroke sets the mask under the brush wherever it goes.
  if (session_->painting() && !painting_rain && brush_.over_terrain &&
      !(brush_.disc() == last_mask_disc_)) {
    const double value = brush_mode_ == BrushMode::kFreeze   ? 0.0
                         : brush_mode_ == BrushMode::kHarden ? 0.2
                                                             : 1.0;
    session_->paint_mask(brush_.disc(), value);
    last_mask_disc_ = brush_.disc();
  }
  if (io.WantCaptureKeyboard) return;
  if (pressed(GLFW_KEY_Z | kCtrl) && !session_->replaying()) {
    message_ = session_->undo() ? "undone: back to the stroke's start"
                                : "nothing to undo (the last " +
                                      std::to_string(Session::kUndoDepth) + " strokes are kept)";
  }
  if (pressed(GLFW_KEY_SPACE)) playing_ = !playing_;
  if (pressed(GLFW_KEY_N)) step_once_ = true;
  if (pressed(GLFW_KEY_R) && !session_->replaying()) session_->reset();
  if (pressed(GLFW_KEY_S)) save_checkpoint();
  if (pressed(GLFW_KEY_P))
    screenshot("runnel-viewer-" + std::to_string(session_->model().steps()) + ".png");
  if (pressed(GLFW_KEY_V)) toggle_recording();
  if (pressed(GLFW_KEY_F) && brush_.over_terrain && can_paint) {
    sources_.push_back(brush_.disc());
    message_ = "source placed: " + with_thousands(brush_.discharge()) + " m3/s";
  }
  if (pressed(GLFW_KEY_D) && brush_.over_terrain && can_paint) {
    RainDisc sink = brush_.disc();
    sink.rate = -1.0;
    sources_.push_back(sink);
    message_ = session_->model().water_view().depth.empty()
                   ? "a sink does nothing here: the model has no standing water"
                   : "sink placed: the water in it drains, its load settles";
  }
  if (pressed(GLFW_KEY_C)) sources_.clear();
  if (pressed(GLFW_KEY_G) && !session_->replaying())
    session_->set_global_rain(!session_->global_rain());
  if (pressed(GLFW_KEY_H)) help_ = !help_;
  if (pressed(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(window_, 1);
}

// The painted rain: the brush while it is down, then the sources. The session logs each change.
void Viewer::update_rain() {
  if (session_->replaying()) return;
  std::vector<RainDisc> discs;
  if (session_->painting() && brush_mode_ == BrushMode::kRain) discs.push_back(brush_.disc());
  discs.insert(discs.end(), sources_.begin(), sources_.end());
  session_->set_rain(discs);
}

// A numerical failure pauses the session with the error on show (and on stderr): undo or reset
// bring back a state that runs.
void Viewer::advance() {
  try {
    advance_unguarded();
  } catch (const Error& e) {
    std::fprintf(stderr, "runnel-viewer: %s (paused)\n", e.what());
    message_ = std::string(e.what()) + " (paused: undo or reset)";
    playing_ = false;
    failed_ = true;
    // Nobody is there to undo in a replay or a run of --frames: end it.
    if (session_->replaying() || options_.frames > 0) glfwSetWindowShouldClose(window_, 1);
  }
}

void Viewer::advance_unguarded() {
  if (session_->replay_finished()) return;
  if (!playing_ && !step_once_) {
    steps_per_second_ = 0;
    return;
  }
  const auto start = Clock::now();
  const std::uint64_t before = session_->model().steps();
  if (recorder_ && !step_once_) {
    // A recorded frame every record_interval of the model's clock, whatever the frame rate.
    session_->advance(record_interval());
  } else {
    // As many steps as fit in about 25 ms, so the window stays responsive at any size.
    int steps = 0;
    do {
      session_->step();
      ++steps;
    } while (!step_once_ && !session_->replay_finished() &&
             Clock::now() - start < std::chrono::milliseconds(25) && steps < 200);
  }
  step_once_ = false;
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  steps_per_second_ =
      static_cast<double>(session_->model().steps() - before) / std::max(seconds, 1e-6);
}

void Viewer::upload() {
  Model& model = session_->model();
  const Heightmap t = model.terrain();
  terrain_->update(t.h, terrain_normals_reference(t));
  const WaterView w = model.water_view();
  water_->update(t.h, w.depth, w.load);
  std::vector<float> depth_speed(2 * t.size(), 0.0f);
  for (std::size_t k = 0; k < w.depth.size(); ++k) {
    depth_speed[2 * k] = w.depth[k];
    depth_speed[2 * k + 1] = w.speed[k];
  }
  terrain_->update_water(depth_speed);
  terrain_->set_depth_scale(static_cast<float>(t.cell));
  std::vector<float> points = w.points;
  for (std::size_t i = 3; i < points.size(); i += 4)  // load → colour: 5 % is full colour
    points[i] = std::min(1.0f, 20.0f * points[i]);
  particles_->update(points);
}

void Viewer::render_scene(int w, int h, bool with_brush) {
  glViewport(0, 0, w, h);
  glClearColor(0.55f, 0.68f, 0.82f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  const glm::mat4 vp = camera_.projection(static_cast<float>(w) / std::max(h, 1)) * camera_.view();
  const float scale = static_cast<float>(std::max(1e-3, 0.02 * (max_height_ - min_height_)));
  terrain_->draw(vp, min_height_, max_height_, overlay_, scale,
                 glm::vec3(brush_.x, brush_.z, brush_.radius), with_brush && brush_.over_terrain);
  const Heightmap& t = session_->model().initial_terrain();
  // Thinner water than 1 % of a cell (2 cm on 2-m cells) is a wet film, not a stream.
  water_->draw(vp, camera_.eye(), static_cast<float>(0.01 * t.cell));
  if (show_particles_) {
    const double spacing = 0.5 * t.cell;
    particles_->draw(vp, static_cast<float>(spacing), static_cast<float>(h), particle_colour_);
  }
}

void Viewer::draw_panel() {
  Model& model = session_->model();
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("runnel");
  int current = 0;
  for (std::size_t k = 0; k < model_names_.size(); ++k)
    if (model_names_[k] == model.info().name) current = static_cast<int>(k);
  if (!session_->replaying() && ImGui::BeginCombo("model", model.info().name.c_str())) {
    for (std::size_t k = 0; k < model_names_.size(); ++k) {
      if (ImGui::Selectable(model_names_[k].c_str(), static_cast<int>(k) == current) &&
          static_cast<int>(k) != current) {
        const std::string name = model_names_[k];
        panel_actions_.push_back([this, name] { session_->switch_model(name); });
      }
    }
    ImGui::EndCombo();
  }
  ImGui::TextWrapped("%s", model.info().class_name.c_str());
  if (session_->replaying())
    ImGui::Text("replaying %s%s", options_.replay.c_str(),
                session_->replay_finished() ? " (finished)" : "");
  if (ImGui::Button(playing_ ? "Pause" : "Play")) playing_ = !playing_;
  ImGui::SameLine();
  if (ImGui::Button("Step")) step_once_ = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset") && !session_->replaying())
    panel_actions_.push_back([this] { session_->reset(); });
  ImGui::SameLine();
  if (ImGui::Button("Reset view")) frame_camera();
  if (ImGui::Button("Undo stroke") && !session_->replaying())
    panel_actions_.push_back([this] { session_->undo(); });
  ImGui::SameLine();
  ImGui::Text("(%zu of %zu kept)", session_->undo_depth(), Session::kUndoDepth);
  if (ImGui::Button("Save checkpoint")) save_checkpoint();
  ImGui::SameLine();
  if (ImGui::Button("Screenshot"))
    screenshot("runnel-viewer-" + std::to_string(model.steps()) + ".png");
  ImGui::SameLine();
  if (ImGui::Button(recorder_ ? "Stop recording" : "Record")) toggle_recording();
  if (recorder_) ImGui::Text("recording: %lld frames", recorder_->frames());
  ImGui::Separator();
  bool rain = session_->global_rain();
  if (model.info().has_rain && ImGui::Checkbox("scenario rain", &rain) && !session_->replaying())
    panel_actions_.push_back([this, rain] { session_->set_global_rain(rain); });
  int mode = static_cast<int>(brush_mode_);
  const char* modes = session_->model().ground()
                          ? "rain\0freeze (mask 0)\0harden (mask 0.2)\0restore (mask 1)\0"
                          : "rain\0";
  if (ImGui::Combo("brush paints", &mode, modes)) brush_mode_ = static_cast<BrushMode>(mode);
  // The brush: a radius in metres and an intensity in mm/h, shown as plain numbers.
  float radius = static_cast<float>(brush_.radius),
        intensity = static_cast<float>(brush_.intensity);
  if (ImGui::SliderFloat("brush radius", &radius, 0.5f, 500.0f, "%.1f m",
                         ImGuiSliderFlags_Logarithmic))
    brush_.radius = radius;
  const std::string shown = with_thousands(brush_.intensity) + " mm/h";
  if (ImGui::SliderFloat("brush rain", &intensity, 10.0f, 1e8f, shown.c_str(),
                         ImGuiSliderFlags_Logarithmic)) {
    brush_.intensity = round_to_nice(intensity);
  }
  ImGui::Text("brush: %s m3/s of water", with_thousands(brush_.discharge()).c_str());
  if (session_->painting()) {
    ImGui::Text("this stroke: %s m3",
                with_thousands(rain_volume_ - session_->stroke_start_volume()).c_str());
  }
  ImGui::Text("water added in all: %s m3", with_thousands(rain_volume_).c_str());
  const auto sinks =
      std::count_if(sources_.begin(), sources_.end(), [](const RainDisc& d) { return d.rate < 0; });
  ImGui::Text("sources: %zu, sinks: %zu (F, D place; C clears)",
              sources_.size() - static_cast<std::size_t>(sinks), static_cast<std::size_t>(sinks));
  int overlay = static_cast<int>(overlay_), colour = static_cast<int>(particle_colour_);
  ImGui::Combo("terrain overlay", &overlay,
               "none\0erosion / deposition\0water depth\0flow speed\0");
  overlay_ = static_cast<TerrainOverlay>(overlay);
  ImGui::Checkbox("particles", &show_particles_);
  if (show_particles_) {
    ImGui::Combo("particle colour", &colour, "sediment load\0flow speed\0");
    particle_colour_ = static_cast<ParticleColour>(colour);
  }
  ImGui::Separator();
  ImGui::Text("%s", model.status().c_str());
  ImGui::Text("steps/s: %.0f   step %llu", steps_per_second_,
              static_cast<unsigned long long>(model.steps()));
  ImGui::Text("time: %.2f%s", model.time(), clock_suffix(model.info().clock));
  ImGui::Text("eroded %.4g m3, deposited %.4g m3", balance_.eroded, balance_.deposited);
  ImGui::Text("mass balance %.2e m3 (rel %.1e)", balance_.residual, balance_.relative);
  ImGui::Text("framerate: %.1f fps", ImGui::GetIO().Framerate);
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
  ImGui::InputText("##checkpoint", load_path_, sizeof load_path_);
  ImGui::SameLine();
  if (ImGui::Button("Open") && !session_->replaying()) {
    const std::string path = load_path_;
    panel_actions_.push_back([this, path] { open(path); });
  }
  if (ImGui::CollapsingHeader("parameters")) {
    for (auto& [key, value] : model.parameters().values()) {
      ImGui::Text("%s = %s", key.c_str(), Parameters::to_text(value).c_str());
    }
  }
  ImGui::End();
  if (help_) {
    ImGui::Begin("help", &help_);
    ImGui::Text("left drag: paint rain   right drag: orbit   middle drag: pan");
    ImGui::Text("wheel: zoom   ctrl/shift + wheel: brush radius");
    ImGui::Text("F: water source at the brush   D: sink   C: clear both   G: scenario rain on/off");
    ImGui::Text("ctrl+Z: undo the last stroke   space: play/pause   N: step   R: reset");
    ImGui::Text("S: save checkpoint   P: screenshot   V: record   H: this help   Esc: quit");
    ImGui::End();
  }
}

void Viewer::print_stats(long long frame, double fps) {
  Model& m = session_->model();
  std::printf("%s\n",
              JsonObject()
                  .add("frame", frame)
                  .add("model", m.info().name)
                  .add("particles", static_cast<long long>(m.water_view().points.size() / 4))
                  .add("steps", static_cast<long long>(m.steps()))
                  .add("steps_per_second", steps_per_second_)
                  .add("rain_volume", rain_volume_)
                  .add("eroded_volume", balance_.eroded)
                  .add("mass_balance_abs", balance_.residual)
                  .add("painting", session_->painting())
                  .add("undo_depth", static_cast<long long>(session_->undo_depth()))
                  .add("recorded_frames", recorder_ ? recorder_->frames() : 0LL)
                  .add("fps", fps)
                  .str()
                  .c_str());
  std::fflush(stdout);
}

// At exit: the session's end in its log, the log and the final state where asked for.
void Viewer::finish() {
  if (!options_.screenshot.empty()) screenshot(options_.screenshot);
  if (!session_->replaying()) session_->end();
  if (!options_.log.empty()) write_session_log(options_.log, session_->log());
  if (!options_.save_at_exit.empty())
    write_checkpoint(options_.save_at_exit, session_->model().checkpoint());
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
    for (auto& action : panel_actions_) action();
    panel_actions_.clear();
    presses_ = std::set<int>(g_key_presses.begin(), g_key_presses.end());
    g_key_presses.clear();
    handle_input();
    update_rain();
    advance();
    if (session_->model_generation() != shown_generation_) on_new_model();
    upload();
    if (frame % 10 == 0) {
      balance_ = session_->model().mass_balance();
      rain_volume_ = session_->model().rain_volume();
    }

    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (recorder_) {
      render_scene(w, h);
      glReadBuffer(GL_BACK);
      recorder_->add(read_framebuffer(w, h));  // the scene, before the brush and the panel
    }
    render_scene(w, h, true);
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
    const bool last = (options_.frames > 0 && frame >= options_.frames) ||
                      (session_->replaying() && session_->replay_finished());
    glfwSwapBuffers(window_);
    if (last) break;
  }
  finish();
  return failed_ ? 1 : 0;
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
