// SPDX-License-Identifier: MIT
#include "runnel/models/memory_check.hpp"

#include <fstream>
#include <string>

#include "runnel/core/error.hpp"
#include "runnel/core/text.hpp"

namespace runnel {

namespace {

std::string gigabytes(double bytes) {
  return format_number(static_cast<double>(static_cast<long long>(bytes / 1e8)) / 10.0) + " GB";
}

}  // namespace

MemoryNeed memory_need(double vertices, double model_bytes_per_vertex, bool ground, int layers) {
  MemoryNeed need;
  need.device_bytes =
      vertices * (model_bytes_per_vertex +
                  (ground ? kGroundBytesPerVertex + kDeviceBytesPerLayerVertex * layers : 0.0));
  need.host_bytes = vertices * kHostBytesPerVertex;
  need.largest_buffer = vertices * 16.0;
  return need;
}

double host_available_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kilobytes = 0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit)
    if (key == "MemAvailable:") return kilobytes * 1024.0;
  return 0;
}

void require_memory(const ComputeContext& compute, const MemoryNeed& need,
                    const std::string& what) {
  const DeviceInfo& device = compute.info();
  const auto global = static_cast<double>(device.global_memory);
  const auto max_alloc = static_cast<double>(device.max_alloc);
  const std::string needs = what + " needs about " + gigabytes(need.device_bytes) +
                            " of device memory and " + gigabytes(need.host_bytes) +
                            " of host memory";
  if (global > 0 && need.device_bytes > global)
    throw runtime_error(needs + "; " + device.name + " has " + gigabytes(global));
  if (max_alloc > 0 && need.largest_buffer > max_alloc)
    throw runtime_error(what + " needs buffers of " + gigabytes(need.largest_buffer) + "; " +
                        device.name + " allocates at most " + gigabytes(max_alloc) + " at once");
  // A CPU device's buffers are host memory: both needs come out of what the host has free.
  const double available = host_available_bytes();
  const double host_need = need.host_bytes + (device.type == "CPU" ? need.device_bytes : 0.0);
  if (available > 0 && host_need > available)
    throw runtime_error(needs + "; this machine has " + gigabytes(available) + " available");
}

}  // namespace runnel
