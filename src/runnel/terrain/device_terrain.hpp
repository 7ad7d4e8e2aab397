// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/compute/context.hpp"
#include "runnel/core/heightmap.hpp"
#include "runnel/terrain/terrain_normals.hpp"

namespace runnel {

// The heightmap and its vertex normals on the device, as every terrain-aware kernel reads them:
// (height, normal, nx, ny, cell) — five kernel arguments in that order.
class DeviceTerrain {
 public:
  DeviceTerrain(ComputeContext& compute, const Heightmap& terrain);
  // Uploads new heights (same size) and recomputes the normals on the device.
  void upload(const Heightmap& terrain);
  void refresh_normals();
  void set_args(cl::Kernel& kernel, cl_uint first_index) const;

  cl::Buffer& height() { return height_; }
  cl::Buffer& normal() { return normal_; }
  int nx() const { return nx_; }
  int ny() const { return ny_; }
  float cell() const { return cell_; }
  double extent_x() const { return (nx_ - 1) * static_cast<double>(cell_); }
  double extent_z() const { return (ny_ - 1) * static_cast<double>(cell_); }

 private:
  ComputeContext& compute_;
  TerrainNormals normals_;
  int nx_, ny_;
  float cell_;
  cl::Buffer height_, normal_;
};

}  // namespace runnel
