// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/core/vertex_normals.hpp"  // the kernel's oracle

namespace runnel {

// Host side of cl/terrain_normals.cl.
class TerrainNormals {
 public:
  explicit TerrainNormals(ComputeContext& compute);
  // Enqueues the kernel on buffers already on the device.
  void enqueue(const cl::Buffer& height, const cl::Buffer& normal, int nx, int ny, float cell);
  // Convenience: upload, compute, read back.
  std::vector<float> compute(const Heightmap& terrain);

 private:
  ComputeContext& compute_;
  Kernel kernel_;
};

}  // namespace runnel
