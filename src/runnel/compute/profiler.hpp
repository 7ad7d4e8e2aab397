// SPDX-License-Identifier: MIT
#pragma once
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "runnel/compute/opencl.hpp"

namespace runnel {

// Launches kernels and, when enabled, times each with OpenCL profiling events, summed per kernel
// name. Disabled, it adds nothing to a launch.
class KernelProfiler {
 public:
  explicit KernelProfiler(cl::CommandQueue& queue) : queue_(queue) {}
  void enable(bool on) { enabled_ = on; }
  bool enabled() const { return enabled_; }

  // Enqueues `kernel` over `global` work-items (exact size; callers round up where they guard).
  // group: the work-group size, 0 to let the device choose.
  void launch(cl::Kernel& kernel, std::size_t global, const char* name, std::size_t group = 0);

  // Waits for the queue and adds the finished launches' times. Seconds per kernel name.
  const std::map<std::string, double>& collect();
  void reset() {
    seconds_.clear();
    calls_.clear();
  }
  const std::map<std::string, long long>& calls() const { return calls_; }

 private:
  cl::CommandQueue& queue_;
  bool enabled_ = false;
  std::vector<std::pair<std::string, cl::Event>> pending_;
  std::map<std::string, double> seconds_;
  std::map<std::string, long long> calls_;
};

}  // namespace runnel
