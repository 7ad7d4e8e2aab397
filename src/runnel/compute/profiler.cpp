// SPDX-License-Identifier: MIT
#include "runnel/compute/profiler.hpp"

namespace runnel {

void KernelProfiler::launch(cl::Kernel& kernel, std::size_t global, const char* name,
                            std::size_t group) {
  if (global == 0) return;
  // A fixed work-group size (Kernel chooses it from the device): PoCL compiles a kernel once per
  // work-group size, and letting it pick one for each new global size would recompile as the
  // particle count changes.
  const cl::NDRange local = group > 0 ? cl::NDRange(group) : cl::NullRange;
  if (!enabled_) {
    queue_.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), local);
    return;
  }
  cl::Event event;
  queue_.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), local, nullptr, &event);
  pending_.emplace_back(name, event);
  // Bound the list: events of a long run are folded in as they complete.
  if (pending_.size() > 4096) collect();
}

const std::map<std::string, double>& KernelProfiler::collect() {
  if (!pending_.empty()) queue_.finish();
  for (auto& [name, event] : pending_) {
    const cl_ulong start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const cl_ulong end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    seconds_[name] += 1e-9 * static_cast<double>(end - start);
    calls_[name] += 1;
  }
  pending_.clear();
  return seconds_;
}

}  // namespace runnel
