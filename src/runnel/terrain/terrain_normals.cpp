// SPDX-License-Identifier: MIT
#include "runnel/terrain/terrain_normals.hpp"

#include "runnel/compute/launch.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {

std::vector<float> terrain_normals_reference(const Heightmap& t) {
  std::vector<float> n(t.size() * 3);
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, t.nx - 1);
      const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, t.ny - 1);
      const double dhdx = (double(t.at(i1, j)) - t.at(i0, j)) / ((i1 - i0) * t.cell);
      const double dhdz = (double(t.at(i, j1)) - t.at(i, j0)) / ((j1 - j0) * t.cell);
      const double len = std::sqrt(dhdx * dhdx + 1.0 + dhdz * dhdz);
      const std::size_t k = static_cast<std::size_t>(j) * t.nx + i;
      n[3 * k + 0] = static_cast<float>(-dhdx / len);
      n[3 * k + 1] = static_cast<float>(1.0 / len);
      n[3 * k + 2] = static_cast<float>(-dhdz / len);
    }
  }
  return n;
}

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
