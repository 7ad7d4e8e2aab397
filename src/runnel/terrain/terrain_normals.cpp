// SPDX-License-Identifier: MIT
#include "runnel/terrain/terrain_normals.hpp"

#include "runnel/compute/launch.hpp"

namespace runnel {

TerrainNormals::TerrainNormals(ComputeContext& compute)
    : compute_(compute),
      kernel_(compute, compute.program({"cl/common.cl", "cl/terrain_normals.cl"}),
              "terrain_normals") {}

void TerrainNormals::enqueue(const cl::Buffer& height, const cl::Buffer& normal, int nx, int ny,
                             float cell) {
  kernel_.set("height", height).set("normal", normal).set("nx", nx).set("ny", ny);
  kernel_.set("cell", cell).launch(round_up_work(static_cast<std::size_t>(nx) * ny));
}

std::vector<float> TerrainNormals::compute(const Heightmap& terrain) {
  auto& ctx = compute_.context();
  cl::Buffer height(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, terrain.size() * sizeof(float),
                    const_cast<float*>(terrain.h.data()));
  cl::Buffer normal(ctx, CL_MEM_WRITE_ONLY, terrain.size() * 3 * sizeof(float));
  enqueue(height, normal, terrain.nx, terrain.ny, static_cast<float>(terrain.cell));
  std::vector<float> out(terrain.size() * 3);
  compute_.queue().enqueueReadBuffer(normal, CL_TRUE, 0, out.size() * sizeof(float), out.data());
  return out;
}

}  // namespace runnel
