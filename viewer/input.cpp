// SPDX-License-Identifier: MIT
// Mouse and keys into session actions: the brush's position (the cursor ray against the terrain),
// strokes of rain or of the ground's mask, sources and sinks, undo, the camera.
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "runnel/terrain/ray_pick.hpp"
#include "viewer.hpp"

namespace runnel::viewer {

void Viewer::handle_input() {
  ImGuiIO& io = ImGui::GetIO();
  double x = 0, y = 0;
  window_.cursor(x, y);
  const double dx = x - last_x_, dy = y - last_y_;
  last_x_ = x;
  last_y_ = y;
  int w = 0, h = 0;
  window_.window_size(w, h);
  if (!io.WantCaptureMouse) {
    if (window_.button_down(GLFW_MOUSE_BUTTON_RIGHT))
      camera_.orbit(static_cast<float>(dx), static_cast<float>(dy));
    if (window_.button_down(GLFW_MOUSE_BUTTON_MIDDLE)) {
      camera_.pan(static_cast<float>(dx), static_cast<float>(dy), static_cast<float>(h));
    }
    if (io.MouseWheel != 0.0f) {
      if (io.KeyCtrl || io.KeyShift)
        brush_.radius = std::max(0.5, brush_.radius * std::pow(1.15, io.MouseWheel));
      else
        camera_.zoom(io.MouseWheel);
    }
  }
  const bool can_paint = handle_brush(x, y, w, h, io.WantCaptureMouse);
  if (!io.WantCaptureKeyboard) handle_keys(can_paint);
}

// The cursor ray against the terrain places the brush; the left button paints a stroke (rain, or a
// mask). Returns whether the brush can paint here.
bool Viewer::handle_brush(double x, double y, int w, int h, bool mouse_on_panel) {
  // The cursor ray against the terrain: where the brush is.
  glm::dvec3 origin, direction;
  camera_.ray(x, y, std::max(w, 1), std::max(h, 1), origin, direction);
  const double o[3] = {origin.x, origin.y, origin.z},
               d[3] = {direction.x, direction.y, direction.z};
  const auto hit = pick_terrain(session_->model().initial_terrain(), o, d);
  brush_.over_terrain = hit.has_value() && !mouse_on_panel;
  if (hit) {
    brush_.x = hit->x;
    brush_.z = hit->z;
  }
  const bool down = window_.button_down(GLFW_MOUSE_BUTTON_LEFT);
  const bool painting_rain = brush_mode_ == BrushMode::kRain;
  const bool rain_mask = brush_mode_ == BrushMode::kDry || brush_mode_ == BrushMode::kWet;
  const bool can_paint = !session_->replaying() &&
                         (painting_rain ? session_->model().interaction().paints_rain()
                                        : session_->has_mask(rain_mask ? "rain" : "erodibility"));
  if (down && !mouse_down_ && brush_.over_terrain && can_paint) session_->begin_stroke();
  if (down && !mouse_down_ && brush_.over_terrain && !can_paint && !session_->replaying()) {
    message_ = painting_rain
                   ? "the " + session_->model().info().name + " model takes no rain"
                   : "no such mask here: the scenario has no [[layers]], masks or rain mask";
  }
  if (!down && session_->painting() && !session_->replaying()) session_->end_stroke();
  mouse_down_ = down && (mouse_down_ || brush_.over_terrain);
  // A mask stroke sets the mask under the brush wherever it goes.
  if (session_->painting() && !painting_rain && brush_.over_terrain &&
      !(brush_.disc() == last_mask_disc_)) {
    const double value = brush_mode_ == BrushMode::kFreeze || brush_mode_ == BrushMode::kDry ? 0.0
                         : brush_mode_ == BrushMode::kHarden                                 ? 0.2
                                                                                             : 1.0;
    session_->paint_mask(brush_.disc(), value, rain_mask ? "rain" : "erodibility");
    last_mask_disc_ = brush_.disc();
  }
  return can_paint;
}

void Viewer::handle_keys(bool can_paint) {
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
    message_ = session_->model().interaction().water_view().depth.empty()
                   ? "a sink does nothing here: the model has no standing water"
                   : "sink placed: the water in it drains, its load settles";
  }
  if (pressed(GLFW_KEY_C)) sources_.clear();
  if (pressed(GLFW_KEY_G) && !session_->replaying())
    session_->set_global_rain(!session_->global_rain());
  if (pressed(GLFW_KEY_H)) help_ = !help_;
  if (pressed(GLFW_KEY_HOME)) frame_camera();
  if (pressed(GLFW_KEY_ESCAPE)) window_.close();
}

// The painted rain: the brush while it is down, then the sources. The session logs each change.
void Viewer::update_rain() {
  if (session_->replaying()) return;
  std::vector<RainDisc> discs;
  if (session_->painting() && brush_mode_ == BrushMode::kRain) discs.push_back(brush_.disc());
  discs.insert(discs.end(), sources_.begin(), sources_.end());
  session_->set_rain(discs);
}

}  // namespace runnel::viewer
