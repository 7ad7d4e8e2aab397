// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/models/interaction.hpp"

namespace runnel {

// The water to draw, on a grid of its own (the viewer's water surface): per vertex, row-major, the
// ground under it (m), its depth (m), its sediment load (m³/m³) and its horizontal velocity (x, z
// interleaved, m/s). Vertex (i, j) lies at (i·cell, j·cell) in the terrain's frame.
struct WaterSurface {
  int nx = 0, ny = 0;
  double cell = 1.0;
  std::vector<float> ground, depth, load, velocity;
};

// The grid models' water as they hold it: the terrain's own grid.
WaterSurface grid_water_surface(const Heightmap& terrain, const WaterView& view);

// SPH's water at the particles' scale (docs/viewer.md, "Water"): a grid of the particle spacing
// (the terrain's cell divided by round(cell / spacing)), on which each particle spreads its volume
// spacing³ with a smooth 2-D kernel of radius twice the spacing, W(r) ∝ (1 − r²/R²)³, normalised
// over the vertices it reaches, so the water's volume is kept to rounding and a uniform layer k
// particles deep reads as a flat surface k·spacing deep. Load and velocity: the volume-weighted
// means. `view.points` and `view.point_velocity` give the particles.
WaterSurface particle_water_surface(const Heightmap& terrain, const WaterView& view,
                                    double spacing);

}  // namespace runnel
