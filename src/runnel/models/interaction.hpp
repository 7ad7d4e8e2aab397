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
  std::vector<float> points;
};

// The vertices of an nx × ny grid of spacing `cell` inside a disc (distance from the centre at most
// the radius): their indices, row-major. Painting adds water to exactly these.
std::vector<int> vertices_in_disc(int nx, int ny, double cell, const RainDisc& disc);

}  // namespace runnel
