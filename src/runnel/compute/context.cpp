// SPDX-License-Identifier: MIT
#include "runnel/compute/context.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "runnel/compute/kernel_sources.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/compute/stderr_capture.hpp"
#include "runnel/core/error.hpp"

namespace runnel {
namespace {

constexpr const char* kNoDeviceHelp =
    "no OpenCL device found: install an OpenCL driver, e.g. 'apt-get install pocl-opencl-icd' for "
    "the CPU "
    "(or the GPU vendor's ICD)";

std::string device_type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string trim(std::string s) {
  while (!s.empty() && (std::isspace(static_cast<unsigned char>(s.back())) || s.back() == '\0'))
    s.pop_back();
  std::size_t start = 0;
  while (start < s.size() && std::isspace(static_cast<unsigned char>(s[start]))) ++start;
  return s.substr(start);
}

std::vector<std::pair<cl::Platform, cl::Device>> all_devices() {
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    throw input_error(kNoDeviceHelp);  // CL_PLATFORM_NOT_FOUND_KHR when no ICD is installed
  }
  std::vector<std::pair<cl::Platform, cl::Device>> out;
  for (auto& p : platforms) {
    std::vector<cl::Device> devices;
    try {
      p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no devices
    }
    for (auto& d : devices) out.emplace_back(p, d);
  }
  if (out.empty()) throw input_error(kNoDeviceHelp);
  return out;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> infos;
  int index = 0, platform_index = -1, device_index = 0;
  cl_platform_id last = nullptr;
  for (auto& [platform, device] : all_devices()) {
    if (platform() != last) {
      last = platform();
      ++platform_index;
      device_index = 0;
    }
    DeviceInfo info;
    info.index = index++;
    info.platform_index = platform_index;
    info.device_index = device_index++;
    info.platform = trim(platform.getInfo<CL_PLATFORM_NAME>());
    info.name = trim(device.getInfo<CL_DEVICE_NAME>());
    info.type = device_type_name(device.getInfo<CL_DEVICE_TYPE>());
    info.version = trim(device.getInfo<CL_DEVICE_VERSION>());
    info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
    info.global_memory = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
    info.local_memory = device.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
    info.max_alloc = device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
    info.preferred_float_width = device.getInfo<CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT>();
    infos.push_back(info);
  }
  return infos;
}

DeviceInfo select_device(const std::string& spec_in) {
  std::string spec = spec_in;
  if (spec.empty()) {
    if (const char* env = std::getenv("RUNNEL_DEVICE")) spec = env;
  }
  const auto devices = list_devices();
  const std::string s = lower(trim(spec));
  auto first_of_type = [&](const std::string& type) -> const DeviceInfo* {
    for (auto& d : devices) {
      if (d.type == type) return &d;
    }
    return nullptr;
  };
  if (s.empty()) {
    if (auto* d = first_of_type("GPU")) return *d;
    if (auto* d = first_of_type("CPU")) return *d;
    return devices.front();
  }
  if (s == "gpu" || s == "cpu") {
    if (auto* d = first_of_type(s == "gpu" ? "GPU" : "CPU")) return *d;
    throw input_error("--device " + spec + ": no " + s + " device (see 'runnel devices')");
  }
  const bool all_digits =
      std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
  if (all_digits && s.size() < 6) {
    const int index = std::stoi(s);
    if (index < static_cast<int>(devices.size())) return devices[index];
    throw input_error("--device " + spec + ": no device with index " + s +
                      " (see 'runnel devices')");
  }
  const auto colon = s.find(':');
  if (colon != std::string::npos && colon > 0 && colon + 1 < s.size() && s.size() < 12 &&
      std::all_of(s.begin(), s.end(),
                  [](unsigned char c) { return std::isdigit(c) || c == ':'; })) {
    const int p = std::stoi(s.substr(0, colon)), d = std::stoi(s.substr(colon + 1));
    for (auto& info : devices) {
      if (info.platform_index == p && info.device_index == d) return info;
    }
    throw input_error("--device " + spec + ": no device " + s + " (see 'runnel devices')");
  }
  for (auto& info : devices) {
    if (lower(info.name).find(s) != std::string::npos ||
        lower(info.platform).find(s) != std::string::npos) {
      return info;
    }
  }
  throw input_error("--device " + spec + ": no device matches (see 'runnel devices')");
}

unsigned device_lanes(const DeviceInfo& device) {
  if (device.type != "CPU") return 8;
  return std::clamp(std::bit_floor(std::max(device.preferred_float_width, 1u)), 4u, kMostLanes);
}

namespace {

// The widths cl/common.cl is written for; `what` names the value in the error.
unsigned checked_lanes(unsigned lanes, const std::string& what) {
  if (lanes == 4 || lanes == 8 || lanes == 16) return lanes;
  throw input_error(what + ": the lane kernels take 4, 8 or 16 lanes");
}

}  // namespace

unsigned lanes_from_environment() {
  const char* env = std::getenv("RUNNEL_LANES");
  if (!env) return 0;
  const std::string value = trim(env);
  const bool digits =
      !value.empty() && value.size() < 4 &&
      std::all_of(value.begin(), value.end(), [](unsigned char c) { return std::isdigit(c); });
  return checked_lanes(digits ? static_cast<unsigned>(std::stoi(value)) : 0,
                       "RUNNEL_LANES=" + value);
}

ComputeContext::ComputeContext(const std::string& device_spec, unsigned lanes) {
  if (lanes != 0) checked_lanes(lanes, "lanes " + std::to_string(lanes));
  info_ = select_device(device_spec);
  if (lanes == 0) lanes = lanes_from_environment();
  lanes_ = lanes != 0 ? lanes : device_lanes(info_);
  const auto devices = all_devices();
  device_ = devices[info_.index].second;
  context_ = cl::Context(device_);
  queue_ = cl::CommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE);
}

ComputeContext::~ComputeContext() {
  try {
    queue_.finish();
  } catch (const cl::Error&) {  // a failed device has nothing left to wait for
  }
}

std::string embedded_source(const std::string& path) {
  for (const auto& source : kernel_sources()) {
    if (path == source.path) return "#line 1 \"" + path + "\"\n" + source.text + "\n";
  }
  throw runtime_error("no embedded OpenCL source '" + path + "'");
}

void ComputeContext::keep_build_log(const std::string& name, const std::string& log) {
  if (trim(log).empty()) return;
  build_logs_[name] += log;
  if (std::getenv("RUNNEL_KERNEL_LOG")) {
    std::fprintf(stderr, "runnel: the compiler's log of %s (built for %u lanes):\n%s\n",
                 name.c_str(), lanes_, log.c_str());
  }
}

cl::Program ComputeContext::build_source(const std::string& source, const std::string& options,
                                         Division division, const std::string& name) {
  cl::Program program(context_, source);
  // Fixed math options so every device computes the same way: no fast-math, denormals as the device
  // has them, and divisions and square roots correctly rounded wherever the device offers it unless
  // the program asks for the device's own (Division; measured on an H200, docs/gpu.md).
  // -cl-kernel-arg-info: so Kernel can check its argument names against the compiler's.
  // -DLANES: the items a work-item of a lane kernel takes (cl/common.cl).
  const bool exact_division =
      division == Division::exact &&
      (device_.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  const std::string all_options =
      std::string("-cl-std=CL1.2 -cl-kernel-arg-info ") +
      (exact_division ? "-cl-fp32-correctly-rounded-divide-sqrt " : "") +
      "-DLANES=" + std::to_string(lanes_) + " " + options;
  auto build_log = [&] {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device_);
    } catch (const cl::Error&) {
    }
    return log;
  };
  StderrCapture compiler_output;
  try {
    program.build({device_}, all_options.c_str());
  } catch (const cl::Error& e) {
    const std::string said = compiler_output.release();
    const std::string log = build_log() + said;
    // Lead with the first diagnostic line (file:line:col: error: ...), then the whole log.
    std::string first;
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);) {
      if (line.find("error") != std::string::npos) {
        first = line;
        break;
      }
    }
    throw runtime_error("OpenCL kernel build failed: " +
                        (first.empty() ? std::string(cl_error_name(e.err())) : first) +
                        "\n--- compiler log ---\n" + log);
  }
  const std::string said = compiler_output.release();
  keep_build_log(name, build_log() + said);
  built_.push_back({name, source, all_options});
  return program;
}

cl::Program& ComputeContext::program(const std::vector<std::string>& files,
                                     const std::string& options, Division division) {
  std::string key = options + (division == Division::exact ? "|exact" : "|device");
  std::string name;
  for (auto& f : files) {
    key += "|" + f;
    name += (name.empty() ? "" : " + ") + f;
  }
  auto it = programs_.find(key);
  if (it != programs_.end()) return it->second;
  std::string source;
  for (auto& f : files) source += embedded_source(f);
  return programs_.emplace(key, build_source(source, options, division, name)).first->second;
}

const char* cl_error_name(int code) {
  switch (code) {
    case CL_SUCCESS:
      return "CL_SUCCESS";
    case CL_DEVICE_NOT_FOUND:
      return "CL_DEVICE_NOT_FOUND";
    case CL_DEVICE_NOT_AVAILABLE:
      return "CL_DEVICE_NOT_AVAILABLE";
    case CL_COMPILER_NOT_AVAILABLE:
      return "CL_COMPILER_NOT_AVAILABLE";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
      return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES:
      return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY:
      return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE:
      return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE:
      return "CL_INVALID_VALUE";
    case CL_INVALID_BUFFER_SIZE:
      return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_KERNEL_ARGS:
      return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_WORK_GROUP_SIZE:
      return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_GLOBAL_WORK_SIZE:
      return "CL_INVALID_GLOBAL_WORK_SIZE";
    case CL_INVALID_ARG_INDEX:
      return "CL_INVALID_ARG_INDEX";
    case CL_INVALID_ARG_VALUE:
      return "CL_INVALID_ARG_VALUE";
    case CL_INVALID_ARG_SIZE:
      return "CL_INVALID_ARG_SIZE";
    case CL_INVALID_KERNEL_NAME:
      return "CL_INVALID_KERNEL_NAME";
    case CL_INVALID_MEM_OBJECT:
      return "CL_INVALID_MEM_OBJECT";
    case CL_INVALID_COMMAND_QUEUE:
      return "CL_INVALID_COMMAND_QUEUE";
    default:
      return "CL error";
  }
}

}  // namespace runnel
