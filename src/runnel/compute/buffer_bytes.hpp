// SPDX-License-Identifier: MIT
#pragma once
#include <initializer_list>

#include "runnel/compute/opencl.hpp"

namespace runnel {

// The bytes the device holds for these buffers, as OpenCL reports them (CL_MEM_SIZE): what a
// model's memory figure adds up, so that it cannot drift from what the model allocates. A buffer
// never created counts 0.
inline double buffer_bytes(std::initializer_list<const cl::Buffer*> buffers) {
  double bytes = 0;
  for (const cl::Buffer* b : buffers) {
    if ((*b)() != nullptr) bytes += static_cast<double>(b->getInfo<CL_MEM_SIZE>());
  }
  return bytes;
}

}  // namespace runnel
