// SPDX-License-Identifier: MIT
#include "runnel/compute/profiler.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "runnel/core/error.hpp"

namespace runnel {

KernelProfiler::~KernelProfiler() {
  // No collect() here (it may throw): a trace still open keeps the launches collected so far.
  if (trace_ != nullptr) end_trace();
}

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
    const cl_ulong wait = last_end_ > 0 && start > last_end_ ? start - last_end_ : 0;
    waits_[name] += 1e-9 * static_cast<double>(wait);
    last_end_ = end;
    if (trace_ != nullptr) {
      const cl_ulong queued = event.getProfilingInfo<CL_PROFILING_COMMAND_QUEUED>();
      if (trace_empty_) trace_origin_ = std::min(queued, start);
      auto us = [&](cl_ulong t) { return 1e-3 * static_cast<double>(t - trace_origin_); };
      std::fprintf(trace_,
                   "%s{\"name\": \"%s\", \"ph\": \"X\", \"pid\": 1, \"tid\": 1, \"ts\": %.3f, "
                   "\"dur\": %.3f, \"args\": {\"queued_us\": %.3f, \"wait_us\": %.3f}}",
                   trace_empty_ ? "\n" : ",\n", name.c_str(), us(start),
                   1e-3 * static_cast<double>(end - start), us(queued),
                   1e-3 * static_cast<double>(wait));
      trace_empty_ = false;
    }
  }
  pending_.clear();
  return seconds_;
}

double KernelProfiler::idle_seconds() const {
  double idle = 0;
  for (const auto& [name, seconds] : waits_) idle += seconds;
  return idle;
}

void KernelProfiler::reset() {
  seconds_.clear();
  waits_.clear();
  calls_.clear();
  last_end_ = 0;
}

void KernelProfiler::trace_to(const std::string& path) {
  close_trace();
  trace_ = std::fopen(path.c_str(), "w");
  if (trace_ == nullptr)
    throw input_error("--trace " + path + ": cannot be written (" + std::strerror(errno) + ")");
  std::fputs("[", trace_);
  trace_empty_ = true;
}

void KernelProfiler::close_trace() {
  if (trace_ == nullptr) return;
  if (!pending_.empty()) collect();
  end_trace();
}

void KernelProfiler::end_trace() {
  std::fputs("\n]\n", trace_);
  std::fclose(trace_);
  trace_ = nullptr;
}

}  // namespace runnel
