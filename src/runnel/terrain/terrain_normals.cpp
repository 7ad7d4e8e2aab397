// SPDX-License-Identifier: MIT
#include "runnel/terrain/terrain_normals.hpp"

#include "runnel/compute/launch.hpp"

namespace runnel {

TerrainNormals::TerrainNormals(ComputeContext& compute)
    : compute_(compute),
      kernel_(compute, compute.program({"cl/common.cl", "cl/terrain_normals.cl"}),
              "terrain_normals"),
      no_contact_(compute.context(), CL_MEM_READ_WRITE, sizeof(float)) {}

void TerrainNormals::enqueue(const cl::Buffer& height, const cl::Buffer& normal, int nx, int ny,
                             float cell, const cl::Buffer& stale, int tiles_x,
                             const cl::Buffer* contact, float contact_radius) {
  kernel_.set("height", height).set("normal", normal).set("nx", nx).set("ny", ny);
  kernel_.set("cell", cell).set("stale", stale).set("tiles_x", tiles_x);
  kernel_.set("carry_contact", cl_int{contact != nullptr}).set("contact_radius", contact_radius);
  kernel_.set("contact", contact ? *contact : no_contact_);
  kernel_.launch(round_up_work(static_cast<std::size_t>(nx) * ny));
}

std::vector<float> TerrainNormals::compute(const Heightmap& terrain) {
  auto& ctx = compute_.context();
  cl::Buffer height(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, terrain.size() * sizeof(float),
                    const_cast<float*>(terrain.h.data()));
  cl::Buffer normal(ctx, CL_MEM_WRITE_ONLY, terrain.size() * 3 * sizeof(float));
  const int tiles_x = terrain_tiles(terrain.nx);
  std::vector<cl_uint> every_tile(static_cast<std::size_t>(tiles_x) * terrain_tiles(terrain.ny), 1);
  cl::Buffer stale(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                   every_tile.size() * sizeof(cl_uint), every_tile.data());
  enqueue(height, normal, terrain.nx, terrain.ny, static_cast<float>(terrain.cell), stale, tiles_x);
  std::vector<float> out(terrain.size() * 3);
  compute_.queue().enqueueReadBuffer(normal, CL_TRUE, 0, out.size() * sizeof(float), out.data());
  return out;
}

}  // namespace runnel
