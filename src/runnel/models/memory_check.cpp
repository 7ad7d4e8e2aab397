// SPDX-License-Identifier: MIT
#include "runnel/models/memory_check.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <sstream>
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

namespace {

// The address space mapped now (VmSize of /proc/self/status), bytes; 0 when unknown.
double mapped_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmSize:", 0) == 0) {
      std::istringstream in(line.substr(7));
      double kilobytes = 0;
      in >> kilobytes;
      return kilobytes * 1024.0;
    }
  return 0;
}

// A number from a cgroup file ("max": none), bytes; -1 when there is none.
double cgroup_value(const std::string& path) {
  std::ifstream f(path);
  std::string text;
  if (!(f >> text) || text == "max") return -1;
  try {
    return std::stod(text);
  } catch (const std::exception&) {
    return -1;
  }
}

// What the process's cgroup (v2) leaves: memory.max less memory.current; -1 when unlimited.
double cgroup_room() {
  std::ifstream self("/proc/self/cgroup");
  std::string line;
  while (std::getline(self, line)) {
    if (line.rfind("0::", 0) != 0) continue;
    const std::string dir = "/sys/fs/cgroup" + line.substr(3);
    const double most = cgroup_value(dir + "/memory.max");
    if (most < 0) return -1;
    const double used = std::max(cgroup_value(dir + "/memory.current"), 0.0);
    return std::max(most - used, 0.0);
  }
  return -1;
}

}  // namespace

MemoryRoom memory_room() {
  MemoryRoom room{host_available_bytes(), "this machine"};
  auto consider = [&room](double bytes, const char* by) {
    if (bytes >= 0 && (room.bytes <= 0 || bytes < room.bytes)) room = {bytes, by};
  };
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    consider(std::max(static_cast<double>(limit.rlim_cur) - mapped_bytes(), 0.0),
             "the address-space limit (ulimit -v)");
  consider(cgroup_room(), "the cgroup's memory.max");
  return room;
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
  // A CPU device's buffers are host memory: both needs come out of what the process may still
  // take (the host's free memory, or less under a ulimit or a cgroup).
  const MemoryRoom room = memory_room();
  const double host_need = need.host_bytes + (device.type == "CPU" ? need.device_bytes : 0.0);
  if (room.bytes > 0 && host_need > room.bytes)
    throw runtime_error(needs + "; " + room.limited_by + " leaves " + gigabytes(room.bytes));
}

}  // namespace runnel
