// SPDX-License-Identifier: MIT
// The ImGui panel (model, play, undo, brush, overlays, statistics) and the stats line on stdout.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "runnel/io/json.hpp"
#include "viewer.hpp"

namespace runnel::viewer {

void Viewer::draw_panel() {
  Model& model = session_->model();
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("runnel");
  panel_run_controls(model);
  panel_brush_controls(model);
  panel_readout(model);
  ImGui::End();
  if (help_) draw_help();
}

// The model, play and step, undo, and the files: checkpoint, screenshot, recording.
void Viewer::panel_run_controls(Model& model) {
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
  // --sim-share: more simulated time a second, or more frames.
  float share = static_cast<float>(options_.sim_share);
  if (ImGui::SliderFloat("sim share", &share, 0.1f, 0.95f, "%.2f of a frame"))
    options_.sim_share = share;
}

// What the brush paints, its radius and rain, the water it added, the overlays.
void Viewer::panel_brush_controls(Model& model) {
  ImGui::Separator();
  bool rain = session_->global_rain();
  if (model.info().has_rain && ImGui::Checkbox("scenario rain", &rain) && !session_->replaying())
    panel_actions_.push_back([this, rain] { session_->set_global_rain(rain); });
  int mode = static_cast<int>(brush_mode_);
  const char* modes =
      session_->has_mask("rain")
          ? "rain\0freeze (mask 0)\0harden (mask 0.2)\0restore (mask 1)\0dry (rain mask "
            "0)\0wet (rain mask 1)\0"
      : session_->has_mask("erodibility")
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
  // What the overlay's colours mean, with its scale.
  const double cell = session_->model().initial_terrain().cell;
  if (overlay_ == TerrainOverlay::kErosion)
    ImGui::Text("red eroded, blue deposited: full colour at %.3g m", erosion_overlay_scale());
  if (overlay_ == TerrainOverlay::kWaterDepth)
    ImGui::Text("blue: water depth, full colour at %.3g m", cell);
  if (overlay_ == TerrainOverlay::kFlowSpeed)
    ImGui::Text("blue slow to yellow fast: full colour at 15 m/s");
  ImGui::TextDisabled("water: clear where thin (the bed shows through),");
  ImGui::TextDisabled("blue-green where deep; brown tint: its sediment;");
  ImGui::TextDisabled("pale streaks: its flow");
  ImGui::Checkbox("particles", &show_particles_);
  if (show_particles_) {
    ImGui::Combo("particle colour", &colour, "sediment load\0flow speed\0");
    particle_colour_ = static_cast<ParticleColour>(colour);
  }
}

// The model's state: steps, time, the mass balance, messages, and a checkpoint to open.
void Viewer::panel_readout(Model& model) {
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
}

void Viewer::draw_help() {
  ImGui::Begin("help", &help_);
  ImGui::Text("left drag: paint rain   right drag: orbit   middle drag: pan");
  ImGui::Text("wheel: zoom   ctrl/shift + wheel: brush radius");
  ImGui::Text("F: water source at the brush   D: sink   C: clear both   G: scenario rain on/off");
  ImGui::Text("ctrl+Z: undo the last stroke   space: play/pause   N: step   R: reset");
  ImGui::Text("Home: frame the whole terrain again (the panel's Reset view)");
  ImGui::Text("S: save checkpoint   P: screenshot   V: record   H: this help   Esc: quit");
  ImGui::End();
}

void Viewer::print_bench(long long frames) {
  Model& m = session_->model();
  const double wall = std::chrono::duration<double>(Clock::now() - bench_start_.wall).count();
  const long long timed = frames - kBenchWarmupFrames;
  JsonObject phases;  // ms a frame
  for (int p = 0; p < FrameTimer::kPhases; ++p)
    phases.add(FrameTimer::kNames[p],
               1e3 * timer_.seconds(static_cast<FrameTimer::Phase>(p)) / std::max(timed, 1LL));
  const double water_draw = water_draw_seconds();
  const double water =
      timer_.seconds(FrameTimer::kWaterSurface) / std::max(timed, 1LL) + water_draw;
  const double drawing = timer_.total() - timer_.seconds(FrameTimer::kSimulate) -
                         timer_.seconds(FrameTimer::kReadWater);
  std::printf("%s\n",
              JsonObject()
                  .add("model", m.info().name)
                  .add("solver", m.info().name == "sph" ? m.parameters().text("sph.solver") : "")
                  .add("particles", static_cast<long long>(particles_shown_))
                  .add("width", static_cast<long long>(options_.width))
                  .add("height", static_cast<long long>(options_.height))
                  .add("frames", timed)
                  .add("wall_seconds", wall)
                  .add("fps", timed / std::max(wall, 1e-9))
                  .add("display", window_.api())
                  .add("gl_renderer", reinterpret_cast<const char*>(glGetString(GL_RENDERER)))
                  .add("draw_share", drawing / std::max(wall, 1e-9))
                  .add("water_share", water * timed / std::max(wall, 1e-9))
                  .add("water_draw_ms", 1e3 * water_draw)
                  .add("ms_per_frame", phases)
                  .add("simulated_seconds_per_wall_second",
                       (m.time() - bench_start_.time) / std::max(wall, 1e-9))
                  .add("steps_per_second",
                       static_cast<double>(m.steps() - bench_start_.steps) / std::max(wall, 1e-9))
                  .str()
                  .c_str());
  std::fflush(stdout);
}

void Viewer::print_stats(long long frame, double fps) {
  Model& m = session_->model();
  std::printf("%s\n", JsonObject()
                          .add("frame", frame)
                          .add("model", m.info().name)
                          .add("particles", static_cast<long long>(particles_shown_))
                          .add("steps", static_cast<long long>(m.steps()))
                          .add("time", m.time())
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

}  // namespace runnel::viewer
