// SPDX-License-Identifier: MIT
#pragma once
// The viewer's state and its parts: viewer.cpp (loading, stepping, drawing, the frame loop),
// input.cpp (mouse and keys into session actions), panel.cpp (the ImGui panel, the stats line).
#include <epoxy/gl.h>
// GLFW after the GL loader, which provides the GL declarations.
#include <GLFW/glfw3.h>

#include <chrono>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "app.hpp"
#include "brush.hpp"
#include "camera.hpp"
#include "frame_timer.hpp"
#include "rain_streaks.hpp"
#include "recorder.hpp"
#include "renderers.hpp"
#include "runnel/compute/context.hpp"
#include "runnel/interactive/session.hpp"
#include "window.hpp"

namespace runnel::viewer {

using Clock = std::chrono::steady_clock;

// Key presses since the viewer last took them (the GLFW key callback, which ImGui chains to).
// A press with ctrl held is the key plus kCtrl: the modifiers come with the event, since ctrl may
// be up again by the time the frame looks.
constexpr int kCtrl = 1 << 20;
std::vector<int>& key_presses();

class Viewer {
 public:
  Viewer(const ViewerOptions& options, Window& window)
      : options_(options), window_(window), compute_(options.device) {
    timer_ = FrameTimer(options.bench);
    load();
  }

  int loop();

 private:
  void load();
  void on_new_model();
  void save_checkpoint();
  void frame_camera();
  // The height change the erosion overlay shows in full colour: 2 % of the relief, m.
  float erosion_overlay_scale() const;
  void screenshot(const std::string& path);
  void screenshot_window(int width, int height);
  void toggle_recording();
  void handle_input();
  bool handle_brush(double x, double y, int w, int h, bool mouse_on_panel);
  void handle_keys(bool can_paint);
  void update_rain();
  void advance();
  void advance_unguarded();
  void upload();
  // The terrain, the water and (when shown) the particles; the brush ring only on the screen, not
  // in screenshots and recordings.
  void render_scene(int width, int height, bool with_brush = false);
  void draw_panel();
  void panel_run_controls(Model& model);
  void panel_brush_controls(Model& model);
  void panel_readout(Model& model);
  void draw_help();
  void print_stats(long long frame, double fps);
  // --bench: the timed frames' rates, as one JSON line.
  void print_bench(long long frames);
  // --bench: what drawing the water adds to a picture of the window's size, s (the scene drawn
  // offscreen with and without it, alternately).
  double water_draw_seconds();
  bool hide_water_ = false;
  struct BenchStart {
    Clock::time_point wall;
    double time = 0;
    std::uint64_t steps = 0;
  } bench_start_;
  FrameTimer timer_{false};  // --bench: the timed frames, phase by phase
  void finish();
  double record_interval() const;
  // A key that went down since the last frame, from the key events (key_presses()): polling the
  // key's state misses a press and release that arrive together (a quick tap, xdotool key).
  bool pressed(int key) const { return presses_.count(key) > 0; }
  std::set<int> presses_;

  ViewerOptions options_;
  Window& window_;
  ComputeContext compute_;
  std::unique_ptr<Session> session_;
  std::uint64_t shown_generation_ = 0;  // the session's model the renderers were built for
  std::unique_ptr<TerrainRenderer> terrain_;
  std::unique_ptr<WaterLayer> water_;
  std::unique_ptr<ParticleRenderer> particles_;
  std::unique_ptr<RainStreaks> rain_;  // the painted rain under the brush
  std::unique_ptr<FrameRecorder> recorder_;
  double record_start_ = 0;  // the model's clock when the recording started
  OrbitCamera camera_;
  bool window_shot_taken_ = false;  // --screenshot-panel: the window's shot is written
  Brush brush_;
  std::vector<RainDisc> sources_;
  // What the brush paints: rain, or the ground's erodibility mask (layered ground only).
  enum class BrushMode { kRain = 0, kFreeze = 1, kHarden = 2, kRestore = 3, kDry = 4, kWet = 5 };
  BrushMode brush_mode_ = BrushMode::kRain;
  RainDisc last_mask_disc_;
  bool playing_ = true, step_once_ = false, help_ = false, show_particles_ = false;
  bool mouse_down_ = false, failed_ = false;
  TerrainOverlay overlay_ = TerrainOverlay::kNone;
  ParticleColour particle_colour_ = ParticleColour::kSediment;
  float min_height_ = 0, max_height_ = 1;
  double steps_per_second_ = 0;
  Clock::time_point advanced_ = Clock::now();  // when the last frame's steps ended
  double last_x_ = 0, last_y_ = 0;
  MassBalance balance_;
  double rain_volume_ = 0;
  std::size_t particles_shown_ = 0;  // water particles in the last upload
  std::string message_;
  std::vector<std::string> model_names_;
  // What the panel asked for, done at the next frame's start: a model replaced in the middle of
  // drawing the panel would leave it reading a model that is gone.
  std::vector<std::function<void()>> panel_actions_;
  void open(const std::string& path);
  char load_path_[512] = "runnel-out/final.h5";
};

}  // namespace runnel::viewer
