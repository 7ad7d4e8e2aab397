// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

namespace runnel {

// What an interactive front end (runnel-viewer) asks of a model beyond running it: rain painted by
// hand, and the water to draw. docs/viewer.md says what each model does with them.

// A disc of painted rain: centre (x, z) and radius in metres from the terrain's first vertex, and
// the rain rate as water depth per second of the model's clock (an iteration counts as a second).
// A negative rate marks a sink: the water standing in the disc drains away each step (models with
// a water depth field; its suspended sediment settles where it is).
struct RainDisc {
  double x = 0, z = 0, radius = 0;
  double rate = 0;  // m/s
  bool operator==(const RainDisc&) const = default;
};

// The water on the terrain, per vertex (row-major, as the heightmap), for display: its depth (m),
// its sediment load (m³ of sediment per m³ of water) and its speed (m/s); empty for a model without
// standing water. `points` holds x, y, z and load of each water particle where the model has them.
struct WaterView {
  std::vector<float> depth, load, speed;
  // The water's horizontal velocity (x, z interleaved, m/s) at each vertex where the model knows
  // it (the pipe model, SPH's particles binned); empty otherwise.
  std::vector<float> velocity;
  std::vector<float> points;
  // Each particle's horizontal velocity (x, z interleaved, m/s), beside `points`.
  std::vector<float> point_velocity;
  double spacing = 0;  // the particles' spacing (m); 0: the model has no particles
};

// The model's side of the interaction, apart from its physics (Model::interactive() gives it):
// painted rain, the scenario's rain switched, the water to draw, the rain mask painted.
class Interactive {
 public:
  virtual ~Interactive() = default;
  // Whether set_painted_rain() does anything.
  virtual bool paints_rain() const = 0;
  // The discs of painted rain from the next step on (empty: none). Their water counts in
  // Model::rain_volume() and, like every state, in the checkpoint.
  virtual void set_painted_rain(const std::vector<RainDisc>& discs) = 0;
  // Turns the model's own (scenario) rain off or back on from the next step; false when the model
  // has none.
  virtual bool set_global_rain(bool on) = 0;
  virtual WaterView water_view() = 0;
  // Sets the rain mask (ground.rain_mask, the fraction of the scenario's rain falling at each
  // vertex) to `value` on these vertices from the next step; false when the scenario has none.
  virtual bool paint_rain_mask(const std::vector<int>& vertices, float value) = 0;
  virtual bool has_rain_mask() const = 0;
};

// The vertices of an nx × ny grid of spacing `cell` inside a disc (distance from the centre at most
// the radius): their indices, row-major. Painting adds water to exactly these.
std::vector<int> vertices_in_disc(int nx, int ny, double cell, const RainDisc& disc);

}  // namespace runnel
