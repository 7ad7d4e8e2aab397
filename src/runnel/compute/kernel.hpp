// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "runnel/compute/context.hpp"

namespace runnel {

// A kernel whose arguments are set by the names of its __kernel signature. The names are read from
// the program's source and, where the platform reports them (CL_KERNEL_ARG_NAME), checked against
// it when the kernel is created; a name the kernel does not have, or an argument left unset at
// launch, throws an error naming the kernel and the argument. So a reordered or renamed argument
// fails at once instead of computing with the wrong buffer.
class Kernel {
 public:
  Kernel() = default;
  Kernel(ComputeContext& compute, cl::Program& program, const std::string& name);

  template <typename T>
  Kernel& set(std::string_view argument, const T& value) {
    const cl_uint index = index_of(argument);
    kernel_.setArg(index, value);
    assigned_[index] = true;
    return *this;
  }
  // Launches over `global` work-items through the profiler, timed under `label` (default: the
  // kernel's name).
  void launch(std::size_t global, const char* label = nullptr);
  // Launches a lane kernel (cl/common.cl) over n items: a work-item per ComputeContext::lanes().
  void launch_lanes(std::size_t n, const char* label = nullptr);
  // Launches `groups` work-groups of `group` work-items each (kernels that share local memory);
  // throws, naming the kernel, when the device cannot run groups that large.
  void launch_groups(std::size_t groups, std::size_t group, const char* label = nullptr);
  // The largest work-group the device runs this kernel in.
  std::size_t max_group() const { return max_group_; }

  const std::string& name() const { return name_; }
  const std::vector<std::string>& arguments() const { return arguments_; }
  bool has(std::string_view argument) const;

 private:
  cl_uint index_of(std::string_view argument) const;
  void check_arguments() const;
  std::size_t max_group_ = 1, default_group_ = 1;
  ComputeContext* compute_ = nullptr;
  std::string name_;
  cl::Kernel kernel_;
  std::vector<std::string> arguments_;
  std::vector<bool> assigned_;
};

// The argument names of `__kernel void name(...)` in OpenCL C source; empty when there is no such
// kernel.
std::vector<std::string> kernel_argument_names(const std::string& source, const std::string& name);

}  // namespace runnel
