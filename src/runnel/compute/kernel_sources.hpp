// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

namespace runnel {

// An OpenCL C source embedded at build time (cmake/embed_kernels.cmake).
struct KernelSource {
  const char* path;  // relative to the repository root, e.g. "cl/terrain_normals.cl"
  const char* text;
};

const std::vector<KernelSource>& kernel_sources();

}  // namespace runnel
