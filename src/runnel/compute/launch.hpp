// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>

#include "runnel/compute/opencl.hpp"

namespace runnel {

// Sets every argument of a kernel in order: set_args(k, a, b, c) == k.setArg(0, a) ... setArg(2,
// c).
template <typename... Args>
void set_args(cl::Kernel& kernel, const Args&... args) {
  cl_uint index = 0;
  (kernel.setArg(index++, args), ...);
}

// Work sizes are rounded up to a multiple of this, so every device can pick a good work-group size;
// kernels guard with `if (i >= n) return;`.
inline constexpr std::size_t kWorkMultiple = 64;
inline std::size_t round_up_work(std::size_t n) {
  return (n + kWorkMultiple - 1) / kWorkMultiple * kWorkMultiple;
}

}  // namespace runnel
