// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "runnel/compute/context.hpp"

namespace runnel {

// What a model on a terrain of `vertices` will hold at most, before any of it is allocated: an
// OpenCL implementation that fails an allocation may abort the process (PoCL does), so a terrain
// too large for the machine must be refused before the first buffer, with the sizes.
struct MemoryNeed {
  double device_bytes = 0;    // the model's buffers
  double host_bytes = 0;      // the terrain's copies, the outputs, the checkpoint
  double largest_buffer = 0;  // one buffer's bytes (a 4-component float field)
};

// Upper bounds, per terrain vertex: the model's own (ModelInfo::device_bytes_per_vertex), and
// what a ground (layers or masks) adds, 44 bytes and 8 a stratum as measured with `runnel run`'s
// figure. A test checks every model's own count of its buffers against them.
inline constexpr double kGroundBytesPerVertex = 64.0;
inline constexpr double kDeviceBytesPerLayerVertex = 16.0;
inline constexpr double kHostBytesPerVertex = 64.0;
MemoryNeed memory_need(double vertices, double model_bytes_per_vertex, bool ground, int layers);

// Throws a runtime error (exit 1) naming `what` and the sizes when the need exceeds the device's
// memory or its largest buffer, or, on a CPU device (whose memory is the host's), the memory the
// host has available now.
void require_memory(const ComputeContext& compute, const MemoryNeed& need, const std::string& what);

// The host's available memory (MemAvailable of /proc/meminfo), bytes; 0 when unknown.
double host_available_bytes();

// The memory this process may still take, and what limits it: the least of the host's available
// memory, what the address-space limit (RLIMIT_AS, `ulimit -v`, as batch systems set it) leaves
// beyond the address space already mapped, and what the process's cgroup leaves (memory.max less
// memory.current, cgroup v2). bytes 0: nothing known.
struct MemoryRoom {
  double bytes = 0;
  std::string limited_by;  // "this machine", "the address-space limit (ulimit -v)", ...
};
MemoryRoom memory_room();

}  // namespace runnel
