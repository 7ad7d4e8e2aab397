// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <vector>

namespace runnel {

// A terrain heightmap: nx × ny vertices, spacing `cell` metres, heights in metres.
// Vertex (i, j) sits at world (i·cell, h, j·cell): x east, z south (grid rows), y up.
// Storage is row-major with i fastest: h[j·nx + i].
struct Heightmap {
  int nx = 0;
  int ny = 0;
  double cell = 1.0;      // m
  double origin_x = 0.0;  // m, world position of vertex (0,0) as read from a georeferenced file
  double origin_z = 0.0;  // m
  std::vector<float> h;   // m

  Heightmap() = default;
  Heightmap(int nx_, int ny_, double cell_, float fill = 0.0f)
      : nx(nx_), ny(ny_), cell(cell_), h(static_cast<std::size_t>(nx_) * ny_, fill) {}

  std::size_t size() const { return h.size(); }
  float& at(int i, int j) { return h[static_cast<std::size_t>(j) * nx + i]; }
  float at(int i, int j) const { return h[static_cast<std::size_t>(j) * nx + i]; }

  float min_height() const;
  float max_height() const;
  // V_terrain = cell² · Σ_v h_v (physics.md §1): the one definition of terrain volume, in m³.
  double volume() const;
};

// Every `factor`-th vertex in each direction (the cell grows by `factor`): a preview of a large
// terrain for pictures.
Heightmap subsample(const Heightmap& t, int factor);

// Hard limits on the size of a terrain, so a corrupt header cannot make us allocate terabytes.
inline constexpr int kMaxSide = 32768;                // vertices per side
inline constexpr long long kMaxVertices = 1LL << 28;  // 268,435,456 vertices (1 GiB of floats)

}  // namespace runnel
