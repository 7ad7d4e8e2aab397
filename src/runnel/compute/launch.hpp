// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>

#include "runnel/compute/opencl.hpp"

namespace runnel {

// Work sizes are rounded up to a multiple of this, so every device can pick a good work-group size;
// kernels guard with `if (i >= n) return;`.
inline constexpr std::size_t kWorkMultiple = 64;
// Items a work-item of a lane kernel takes in the lanes of its vectors (cl/common.cl's LANES,
// which every program is built with).
inline constexpr unsigned kLanes = 8;

inline std::size_t round_up_work(std::size_t n) {
  return (n + kWorkMultiple - 1) / kWorkMultiple * kWorkMultiple;
}
// The work size of a lane kernel over n items: a work-item per kLanes of them.
inline std::size_t lane_work(std::size_t n) {
  return round_up_work((n + kLanes - 1) / kLanes);
}

}  // namespace runnel
