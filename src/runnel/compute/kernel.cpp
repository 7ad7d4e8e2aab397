// SPDX-License-Identifier: MIT
#include "runnel/compute/kernel.hpp"

#include <algorithm>
#include <cctype>

#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"

namespace runnel {

std::vector<std::string> kernel_argument_names(const std::string& source, const std::string& name) {
  std::size_t at = 0;
  while ((at = source.find("__kernel", at)) != std::string::npos) {
    at += 8;
    // Kernels return void; attributes such as reqd_work_group_size((...)) may come before it.
    const std::size_t void_at = source.find("void", at);
    if (void_at == std::string::npos) break;
    at = void_at + 4;
    const std::size_t open = source.find('(', at);
    if (open == std::string::npos) break;
    // The identifier just before the parenthesis is the kernel's name.
    std::size_t end = open;
    while (end > at && std::isspace(static_cast<unsigned char>(source[end - 1]))) --end;
    std::size_t begin = end;
    while (begin > at && (std::isalnum(static_cast<unsigned char>(source[begin - 1])) ||
                          source[begin - 1] == '_'))
      --begin;
    if (source.compare(begin, end - begin, name) != 0) continue;
    // Split the parameter list at depth-0 commas; each parameter's last identifier is its name.
    std::vector<std::string> names;
    int depth = 0;
    std::size_t from = open + 1;
    for (std::size_t k = open + 1; k < source.size(); ++k) {
      const char c = source[k];
      if (c == '(') ++depth;
      if ((c == ',' && depth == 0) || (c == ')' && depth == 0)) {
        std::size_t e = k;
        while (e > from &&
               !(std::isalnum(static_cast<unsigned char>(source[e - 1])) || source[e - 1] == '_'))
          --e;
        std::size_t b = e;
        while (b > from &&
               (std::isalnum(static_cast<unsigned char>(source[b - 1])) || source[b - 1] == '_'))
          --b;
        if (e > b) names.push_back(source.substr(b, e - b));
        from = k + 1;
        if (c == ')') return names;
      } else if (c == ')') {
        --depth;
      }
    }
  }
  return {};
}

Kernel::Kernel(ComputeContext& compute, cl::Program& program, const std::string& name)
    : compute_(&compute), name_(name), kernel_(program, name.c_str()) {
  arguments_ = kernel_argument_names(program.getInfo<CL_PROGRAM_SOURCE>(), name);
  const cl_uint count = kernel_.getInfo<CL_KERNEL_NUM_ARGS>();
  if (arguments_.size() != count) {
    throw runtime_error("kernel " + name + ": its source lists " +
                        std::to_string(arguments_.size()) + " arguments, the compiler " +
                        std::to_string(count));
  }
  for (cl_uint a = 0; a < count; ++a) {
    std::string reported;
    try {
      reported = kernel_.getArgInfo<CL_KERNEL_ARG_NAME>(a);
    } catch (const cl::Error&) {
      break;  // the platform does not report names: the source is the table
    }
    if (reported != arguments_[a]) {
      throw runtime_error("kernel " + name + ": argument " + std::to_string(a) + " is '" +
                          reported + "' to the compiler but '" + arguments_[a] + "' in its source");
    }
  }
  assigned_.assign(count, false);
  // The largest work-group this kernel can run in on this device (a GPU may allow fewer than its
  // device maximum to a kernel that uses many registers): the default group is the largest power
  // of two up to kWorkMultiple within it, so it always divides the rounded global size.
  max_group_ = kernel_.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(compute.device());
  default_group_ = 1;
  while (default_group_ * 2 <= std::min<std::size_t>(max_group_, kWorkMultiple))
    default_group_ *= 2;
}

bool Kernel::has(std::string_view argument) const {
  for (const auto& a : arguments_) {
    if (a == argument) return true;
  }
  return false;
}

cl_uint Kernel::index_of(std::string_view argument) const {
  for (cl_uint a = 0; a < arguments_.size(); ++a) {
    if (arguments_[a] == argument) return a;
  }
  throw runtime_error("kernel " + name_ + " has no argument '" + std::string(argument) + "'");
}

void Kernel::launch(std::size_t global, const char* label) {
  check_arguments();
  // A global size that is not a multiple of the group (tests launch odd sizes): the device picks.
  const std::size_t group = global % default_group_ == 0 ? default_group_ : 0;
  compute_->profiler().launch(kernel_, global, label ? label : name_.c_str(), group);
}

void Kernel::launch_lanes(std::size_t n, const char* label) {
  launch(lane_work(n, compute_->lanes()), label);
}

void Kernel::launch_groups(std::size_t groups, std::size_t group, const char* label) {
  check_arguments();
  if (group > max_group_) {
    throw runtime_error("kernel " + name_ + ": work-groups of " + std::to_string(group) +
                        " work-items, but this device runs it in at most " +
                        std::to_string(max_group_));
  }
  compute_->profiler().launch(kernel_, groups * group, label ? label : name_.c_str(), group);
}

void Kernel::check_arguments() const {
  for (std::size_t a = 0; a < assigned_.size(); ++a) {
    if (!assigned_[a])
      throw runtime_error("kernel " + name_ + ": argument '" + arguments_[a] + "' was never set");
  }
}

}  // namespace runnel
