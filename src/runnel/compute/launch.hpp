// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <cstddef>

#include "runnel/compute/opencl.hpp"

namespace runnel {

// Work sizes are rounded up to a multiple of this, so every device can pick a good work-group size;
// kernels guard with `if (i >= n) return;`.
inline constexpr std::size_t kWorkMultiple = 64;
// The widest a lane kernel's vectors are (cl/common.cl's LANES, ComputeContext::lanes()): buffers
// read a vector at a time are padded to a multiple of it, so their layout is the same on every
// device.
inline constexpr unsigned kMostLanes = 16;

inline std::size_t round_up_work(std::size_t n) {
  return (n + kWorkMultiple - 1) / kWorkMultiple * kWorkMultiple;
}
// The work size of a lane kernel over n items: a work-item per `lanes` of them.
inline std::size_t lane_work(std::size_t n, unsigned lanes) {
  return round_up_work((n + lanes - 1) / lanes);
}

// A pass whose work-items each walk a run of items in order (a stable sort's blocks, a
// compaction, a reduction): n items cut into `runs` runs of `length` (the last may be shorter), at
// least `least_length` long and at most `most_runs` of them.
struct SerialRuns {
  std::size_t runs = 1, length = 0;
};
inline SerialRuns serial_runs(std::size_t n, std::size_t least_length, std::size_t most_runs) {
  SerialRuns r;
  r.runs = std::max<std::size_t>(1, std::min((n + least_length - 1) / least_length, most_runs));
  r.length = (n + r.runs - 1) / r.runs;
  return r;
}

}  // namespace runnel
