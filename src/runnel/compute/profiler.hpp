// SPDX-License-Identifier: MIT
#pragma once
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "runnel/compute/opencl.hpp"

namespace runnel {

// Launches kernels and, when enabled, times each with OpenCL profiling events, summed per kernel
// name. Disabled, it adds nothing to a launch.
//
// It also measures the device's waits: on an in-order queue, the time between one launch's end
// and the next one's start is time the device sat idle, waiting for the host to enqueue (after a
// blocking read, say) or to wake it. With many short kernels a step, those waits can cost as much
// as the kernels (docs/performance.md, "Where the time goes"); they are booked to the kernel
// that waited, so the host code before it is the place to look.
class KernelProfiler {
 public:
  explicit KernelProfiler(cl::CommandQueue& queue) : queue_(queue) {}
  ~KernelProfiler();
  void enable(bool on) { enabled_ = on; }
  bool enabled() const { return enabled_; }

  // Enqueues `kernel` over `global` work-items (exact size; callers round up where they guard).
  // group: the work-group size, 0 to let the device choose.
  void launch(cl::Kernel& kernel, std::size_t global, const char* name, std::size_t group = 0);

  // Waits for the queue and adds the finished launches' times. Seconds per kernel name.
  const std::map<std::string, double>& collect();
  void reset();
  const std::map<std::string, long long>& calls() const { return calls_; }
  // Seconds the device sat idle before each kernel's launches (collect() first).
  const std::map<std::string, double>& waits() const { return waits_; }
  double idle_seconds() const;  // the sum of waits()

  // Writes every launch from now on to `path` as a Chrome trace (the Trace Event Format's JSON
  // array, which Perfetto and chrome://tracing open): one complete event a launch, with the time
  // it was queued and the wait before it. Throws input_error naming the file when it cannot be
  // written. About 150 bytes a launch.
  void trace_to(const std::string& path);
  void close_trace();
  bool tracing() const { return trace_ != nullptr; }

 private:
  cl::CommandQueue& queue_;
  bool enabled_ = false;
  std::vector<std::pair<std::string, cl::Event>> pending_;
  std::map<std::string, double> seconds_, waits_;
  std::map<std::string, long long> calls_;
  cl_ulong last_end_ = 0;  // device clock (ns) at the end of the last collected launch; 0: none
  void end_trace();        // closes the JSON array and the file
  std::FILE* trace_ = nullptr;
  cl_ulong trace_origin_ = 0;  // device clock of the trace's first launch
  bool trace_empty_ = true;
};

}  // namespace runnel
