// SPDX-License-Identifier: MIT
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

DeviceTerrain::DeviceTerrain(ComputeContext& compute, const Heightmap& terrain)
    : compute_(compute),
      normals_(compute),
      nx_(terrain.nx),
      ny_(terrain.ny),
      cell_(static_cast<float>(terrain.cell)),
      height_(compute.context(), CL_MEM_READ_WRITE, terrain.size() * sizeof(float)),
      normal_(compute.context(), CL_MEM_READ_WRITE, terrain.size() * 3 * sizeof(float)) {
  upload(terrain);
}

void DeviceTerrain::upload(const Heightmap& terrain) {
  compute_.queue().enqueueWriteBuffer(height_, CL_TRUE, 0, terrain.size() * sizeof(float),
                                      terrain.h.data());
  refresh_normals();
}

void DeviceTerrain::refresh_normals() {
  normals_.enqueue(height_, normal_, nx_, ny_, cell_);
}

void DeviceTerrain::set_args(cl::Kernel& k, cl_uint i) const {
  k.setArg(i + 0, height_);
  k.setArg(i + 1, normal_);
  k.setArg(i + 2, nx_);
  k.setArg(i + 3, ny_);
  k.setArg(i + 4, cell_);
}

}  // namespace runnel
