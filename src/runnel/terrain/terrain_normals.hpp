// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/core/vertex_normals.hpp"  // the kernel's oracle

namespace runnel {

// The side of a terrain tile in vertices (TERRAIN_TILE in cl/common.cl): the unit in which kernels
// mark the terrain they changed.
inline constexpr int kTerrainTileShift = 4;
inline constexpr int kTerrainTile = 1 << kTerrainTileShift;
inline int terrain_tiles(int vertices) {
  return (vertices + kTerrainTile - 1) >> kTerrainTileShift;
}

// Host side of cl/terrain_normals.cl.
class TerrainNormals {
 public:
  explicit TerrainNormals(ComputeContext& compute);
  // Enqueues the kernel on buffers already on the device, for the vertices of the tiles marked in
  // `stale` (one uint per tile of kTerrainTile² vertices, rows of tiles_x). With `contact`, also
  // the heights of the contact surface `contact_radius` above the terrain into it
  // (DeviceTerrain::carry_contact_surface).
  void enqueue(const cl::Buffer& height, const cl::Buffer& normal, int nx, int ny, float cell,
               const cl::Buffer& stale, int tiles_x, const cl::Buffer* contact = nullptr,
               float contact_radius = 0);
  // Convenience: upload, compute, read back.
  std::vector<float> compute(const Heightmap& terrain);

 private:
  ComputeContext& compute_;
  Kernel kernel_;
  cl::Buffer no_contact_;  // the contact argument when there is none (never written)
};

}  // namespace runnel
