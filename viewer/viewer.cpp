// SPDX-License-Identifier: MIT
// runnel-viewer's core: a Session (src/runnel/interactive) runs the model and logs what the user
// does to it; this file loads it, steps it, draws it and runs the frame loop.
#include "viewer.hpp"

#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "runnel/core/error.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/terrain_normals.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace runnel::viewer {

std::vector<int>& key_presses() {
  static std::vector<int> presses;
  return presses;
}

void Viewer::load() {
  std::string input = options_.input;
  SessionLog replay;
  if (!options_.replay.empty()) {
    replay = read_session_log(options_.replay);
    if (input.empty()) input = replay.input;
    // A log names its input as the session was given it; from elsewhere, beside the log.
    const auto beside = std::filesystem::path(options_.replay).parent_path() / input;
    if (!input.empty() && !std::filesystem::exists(input) && std::filesystem::exists(beside))
      input = beside.string();
    options_.rain = replay.global_rain;
  }
  if (!input.empty() && std::filesystem::path(input).extension() == ".h5") {
    session_ = std::make_unique<Session>(compute_, read_checkpoint(input), input, options_.rain);
  } else {
    Parameters params = input.empty() ? default_parameters() : load_scenario(input);
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
  const bool rain_mask = brush_mode_ == BrushMode::kDry || brush_mode_ == BrushMode::kWet;
  if (brush_mode_ != BrushMode::kRain && !session_->has_mask(rain_mask ? "rain" : "erodibility"))
    brush_mode_ = BrushMode::kRain;
  failed_ = false;
  const Heightmap& t = model.initial_terrain();
  min_height_ = t.min_height();
  max_height_ = std::max(t.max_height(), min_height_ + 1e-3f);
  terrain_ = std::make_unique<TerrainRenderer>(t);
  // Thinner water than 1 % of a cell (2 cm on 2-m cells) is a wet film, not a stream.
  water_ = std::make_unique<WaterLayer>(static_cast<float>(0.01 * t.cell));
  particles_ = std::make_unique<ParticleRenderer>();
  if (!rain_) rain_ = std::make_unique<RainStreaks>();
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

float Viewer::erosion_overlay_scale() const {
  return static_cast<float>(std::max(1e-3, 0.02 * (max_height_ - min_height_)));
}

void Viewer::frame_camera() {
  const Heightmap& t = session_->model().initial_terrain();
  int w = 0, h = 0;
  window_.framebuffer_size(w, h);
  // The vertices of the edges and of a grid of at most 64 × 64 inside: the terrain's silhouette.
  std::vector<glm::vec3> points;
  const int step = std::max(1, std::max(t.nx, t.ny) / 64);
  for (int j = 0; j < t.ny; ++j)
    for (int i = 0; i < t.nx; ++i)
      if ((i % step == 0 && j % step == 0) || i == 0 || j == 0 || i == t.nx - 1 || j == t.ny - 1)
        points.emplace_back(i * t.cell, t.at(i, j), j * t.cell);
  camera_.frame(points, h > 0 ? static_cast<float>(w) / static_cast<float>(h) : 1.6f);
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
  window_.framebuffer_size(w, h);
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

double Viewer::water_draw_seconds() {
  int w = 0, h = 0;
  window_.framebuffer_size(w, h);
  OffscreenTarget target(w, h);
  target.bind();
  double with = 0, without = 0;
  constexpr int kRepeats = 8;
  for (int k = 0; k < 2 * kRepeats; ++k) {
    hide_water_ = k % 2 == 1;
    glFinish();
    const auto start = Clock::now();
    render_scene(w, h);
    glFinish();
    (hide_water_ ? without : with) += std::chrono::duration<double>(Clock::now() - start).count();
  }
  hide_water_ = false;
  OffscreenTarget::unbind();
  return std::max(0.0, with - without) / kRepeats;
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
  record_start_ = session_->model().time();
  message_ = "recording to " + recorder_->target();
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
    if (session_->replaying() || options_.frames > 0) window_.close();
  }
}

void Viewer::advance_unguarded() {
  if (session_->replay_finished()) return;
  if (!playing_ && !step_once_) {
    steps_per_second_ = 0;
    advanced_ = Clock::now();  // a frame's rest is measured from here when it plays again
    return;
  }
  const auto start = Clock::now();
  const std::uint64_t before = session_->model().steps();
  if (recorder_ && !step_once_) {
    // Recorded frame k shows the model at k record_intervals of its clock from the recording's
    // start (the first step at or after it: steps are not shortened, so a recorded replay stays
    // the run it replays), whatever the frame rate.
    const double due =
        record_start_ + static_cast<double>(recorder_->frames() + 1) * record_interval();
    session_->advance(due - session_->model().time());
  } else {
    // The simulation's share of the frame (--sim-share): as many steps as fit in that share of
    // a frame whose other work (drawing, uploading, the panel) took what it took last time, at
    // least 25 ms and at most 250 ms, so the window stays responsive at any size and drawing on
    // a slow GL does not starve the water.
    const double rest = std::chrono::duration<double>(start - advanced_).count();
    const double budget =
        std::clamp(rest * options_.sim_share / (1.0 - options_.sim_share), 0.025, 0.25);
    int steps = 0;
    double elapsed = 0;
    do {
      session_->step();
      ++steps;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      // Another step while it ends nearer the budget than this one does.
    } while (!step_once_ && !session_->replay_finished() &&
             elapsed + 0.5 * elapsed / steps <= budget && steps < 200);
  }
  step_once_ = false;
  advanced_ = Clock::now();
  const double seconds = std::chrono::duration<double>(advanced_ - start).count();
  steps_per_second_ =
      static_cast<double>(session_->model().steps() - before) / std::max(seconds, 1e-6);
}

void Viewer::upload() {
  Model& model = session_->model();
  const Heightmap t = model.terrain();
  terrain_->update(t.h, terrain_normals_reference(t));
  timer_.lap(FrameTimer::kTerrain);
  const WaterView w = model.interaction().water_view();
  timer_.lap(FrameTimer::kReadWater);
  water_->update(w.spacing > 0 ? particle_water_surface(t, w, w.spacing)
                               : grid_water_surface(t, w));
  timer_.lap(FrameTimer::kWaterSurface);
  std::vector<float> depth_speed(2 * t.size(), 0.0f);
  for (std::size_t k = 0; k < w.depth.size(); ++k) {
    depth_speed[2 * k] = w.depth[k];
    depth_speed[2 * k + 1] = w.speed[k];
  }
  terrain_->update_water(depth_speed);
  terrain_->set_depth_scale(static_cast<float>(t.cell));
  particles_shown_ = w.points.size() / 4;
  std::vector<float> points = w.points;
  for (std::size_t i = 3; i < points.size(); i += 4)  // load → colour: 5 % is full colour
    points[i] = std::min(1.0f, 20.0f * points[i]);
  particles_->update(points);
}

void Viewer::render_scene(int w, int h, bool with_brush) {
  glViewport(0, 0, w, h);
  if (options_.water_normals)  // the water's normals alone: black sky and ground
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  else
    glClearColor(0.55f, 0.68f, 0.82f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  const glm::mat4 vp = camera_.projection(static_cast<float>(w) / std::max(h, 1)) * camera_.view();
  const Heightmap& t = session_->model().initial_terrain();
  // The streaks move on the model's clock: they pause with it, and a recording is reproducible.
  // They are a cell wide, whatever grid the water lies on.
  const WaterLook water{camera_.eye(), static_cast<float>(session_->model().time()),
                        static_cast<float>(t.cell), options_.water_normals, hide_water_};
  terrain_->draw(vp,
                 {min_height_, max_height_, overlay_, erosion_overlay_scale(),
                  glm::vec3(brush_.x, brush_.z, brush_.radius), with_brush && brush_.over_terrain},
                 *water_, water);
  if (with_brush) timer_.lap(FrameTimer::kTerrain);  // the window's frame, not a recording's
  if (show_particles_) {
    const double spacing = 0.5 * t.cell;
    particles_->draw(vp, static_cast<float>(spacing), static_cast<float>(h), particle_colour_);
  }
  if (with_brush && brush_.over_terrain && session_->painting() &&
      brush_mode_ == BrushMode::kRain) {  // the painted rain, falling on the brush's ground
    const int i = std::clamp(static_cast<int>(std::lround(brush_.x / t.cell)), 0, t.nx - 1),
              j = std::clamp(static_cast<int>(std::lround(brush_.z / t.cell)), 0, t.ny - 1);
    rain_->draw(vp, glm::vec3(brush_.x, t.at(i, j), brush_.z), static_cast<float>(brush_.radius),
                static_cast<float>(window_.seconds()));
  }
}

// The window as drawn this frame, panel included (--screenshot-panel), before it is shown.
void Viewer::screenshot_window(int w, int h) {
  glReadBuffer(GL_BACK);
  try {
    write_png_rgb(options_.screenshot, read_framebuffer(w, h));
    window_shot_taken_ = true;
  } catch (const Error& e) {
    std::fprintf(stderr, "runnel-viewer: %s\n", e.what());
    failed_ = true;
  }
}

// At exit: the session's end in its log, the log and the final state where asked for.
void Viewer::finish() {
  if (!options_.screenshot.empty() && !window_shot_taken_) screenshot(options_.screenshot);
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
  while (!window_.closing()) {
    window_.poll_events();
    window_.new_imgui_frame();
    ImGui::NewFrame();
    for (auto& action : panel_actions_) action();
    panel_actions_.clear();
    presses_ = std::set<int>(key_presses().begin(), key_presses().end());
    key_presses().clear();
    handle_input();
    update_rain();
    timer_.begin();
    advance();
    timer_.lap(FrameTimer::kSimulate);
    if (session_->model_generation() != shown_generation_) on_new_model();
    upload();
    if (frame % 10 == 0) {
      balance_ = session_->model().mass_balance();
      rain_volume_ = session_->model().rain_volume();
    }

    int w = 0, h = 0;
    window_.framebuffer_size(w, h);
    if (recorder_) {
      render_scene(w, h);
      glReadBuffer(GL_BACK);
      recorder_->add(read_framebuffer(w, h));  // the scene, before the brush and the panel
    }
    timer_.lap(FrameTimer::kOther);
    render_scene(w, h, true);
    draw_panel();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    timer_.lap(FrameTimer::kPanel);

    ++frame;
    ++fps_frames;
    if (options_.bench && frame == kBenchWarmupFrames) {
      bench_start_ = {Clock::now(), session_->model().time(), session_->model().steps()};
      timer_.start_counting();
    }
    const double since = std::chrono::duration<double>(Clock::now() - fps_start).count();
    if (since >= 0.5) {
      fps = fps_frames / since;
      fps_frames = 0;
      fps_start = Clock::now();
    }
    if (options_.stats_every > 0 && frame % options_.stats_every == 0) print_stats(frame, fps);
    const bool last = (options_.frames > 0 && frame >= options_.frames) ||
                      (session_->replaying() && session_->replay_finished());
    if ((last || window_.closing()) && options_.screenshot_panel && !options_.screenshot.empty())
      screenshot_window(w, h);
    window_.present();
    if (last) break;
  }
  if (options_.bench) print_bench(frame);
  finish();
  return failed_ ? 1 : 0;
}

}  // namespace runnel::viewer
