// SPDX-License-Identifier: MIT
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "runnel/compute/opencl.hpp"
#include "runnel/compute/profiler.hpp"

namespace runnel {

// One OpenCL device as `runnel devices` lists it.
struct DeviceInfo {
  int index = 0;  // position in the global list, what `--device N` selects
  int platform_index = 0;
  int device_index = 0;  // within its platform
  std::string platform;
  std::string name;
  std::string type;  // "GPU", "CPU", "accelerator", "other"
  std::string version;
  unsigned compute_units = 0;
  unsigned long long global_memory = 0;  // bytes
  unsigned long long local_memory = 0;   // bytes
  unsigned long long max_alloc = 0;      // bytes
  unsigned preferred_float_width = 1;    // CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT
};

// The lanes a lane kernel (cl/common.cl) takes on a device: a CPU's preferred float vector width
// (its SIMD registers: 4 with SSE, 8 with AVX2, 16 with AVX-512), within 4..16; 8 on a GPU, whose
// lanes are work-items anyway (the width measured there, docs/gpu.md). Results are the same bits
// at every width; docs/performance.md has the measurements behind the choice.
unsigned device_lanes(const DeviceInfo& device);

// The lanes $RUNNEL_LANES asks for (4, 8 or 16), or 0 when it is not set; anything else is an
// input error naming it.
unsigned lanes_from_environment();

// Every device on every platform. Throws an input error naming the package to install when there is
// none.
std::vector<DeviceInfo> list_devices();

// The device that `spec` selects. Empty spec: $RUNNEL_DEVICE, else the first GPU, else the first
// CPU. Spec forms: "gpu", "cpu", an index from `runnel devices`, "P:D" (platform:device) or a name
// substring.
DeviceInfo select_device(const std::string& spec);

// The OpenCL context, device and in-order queue (with profiling) that a simulation runs on,
// and the programs built from the embedded cl/ sources.
class ComputeContext {
 public:
  // lanes: the width of the lane kernels (4, 8 or 16); 0 takes $RUNNEL_LANES, else device_lanes().
  explicit ComputeContext(const std::string& device_spec = "", unsigned lanes = 0);
  // Waits for what is still queued: an error thrown between launches must not let the process exit
  // while the device works (PoCL compiles a kernel for its first launch in a worker thread, and an
  // exit under that compile crashed with a segmentation fault instead of the error's exit 2).
  ~ComputeContext();
  ComputeContext(const ComputeContext&) = delete;
  ComputeContext& operator=(const ComputeContext&) = delete;

  const DeviceInfo& info() const { return info_; }
  // Whether the device wants thousands of work-items in flight (a GPU) rather than a few long ones
  // (a CPU, whose threads each take whole work-groups): passes made of serial runs (the sort, the
  // step statistics) cut their work by it, and the result does not depend on the cut.
  bool wide() const { return wide_override_ ? *wide_override_ : info_.type != "CPU"; }
  // Tests run a GPU's cut on the CPU (the results must be the same bits).
  void set_wide(bool wide) { wide_override_ = wide; }
  // The items a work-item of a lane kernel takes (cl/common.cl's LANES, which every program is
  // built with): fixed for the context's life.
  unsigned lanes() const { return lanes_; }
  // What the compiler said while building each program that built (warnings, remarks), by the
  // program's files; empty logs left out. Printed to stderr as it comes with $RUNNEL_KERNEL_LOG
  // set; a build that fails throws with its log.
  const std::map<std::string, std::string>& build_logs() const { return build_logs_; }
  // Every program built, as it was given to the compiler: the kernels' portability test compiles
  // them again for other targets.
  struct BuiltProgram {
    std::string name, source, options;
  };
  const std::vector<BuiltProgram>& built_programs() const { return built_; }
  cl::Context& context() { return context_; }
  cl::Device& device() { return device_; }
  cl::CommandQueue& queue() { return queue_; }
  // Every kernel launch goes through here, so profiling can time each one (`runnel bench`).
  KernelProfiler& profiler() { return profiler_; }

  // How a program divides and takes square roots. exact: correctly rounded wherever the device
  // offers it, so that the kernels agree with their C++ oracles and with a CPU bit for bit (a GPU's
  // default division is within 2.5 ulp: x / x need not be 1). device: the device's own, for a
  // program whose results are compared within tolerances and are another device's bits anyway
  // (the SPH passes on a GPU sum in another order). PoCL rounds correctly either way.
  enum class Division { exact, device };
  // Builds (once, then cached) a program from embedded files, e.g. {"cl/common.cl", "cl/hash.cl"}.
  // A compile error throws with the compiler log; its lines name the file and line of the fault.
  cl::Program& program(const std::vector<std::string>& files, const std::string& options = "",
                       Division division = Division::exact);
  // Builds a program from source text (used by tests to check error reporting).
  cl::Program build_source(const std::string& source, const std::string& options = "",
                           Division division = Division::exact, const std::string& name = "source");

 private:
  DeviceInfo info_;
  unsigned lanes_ = 8;
  std::optional<bool> wide_override_;
  cl::Context context_;
  cl::Device device_;
  cl::CommandQueue queue_;
  KernelProfiler profiler_{queue_};
  std::map<std::string, cl::Program> programs_;
  std::map<std::string, std::string> build_logs_;
  std::vector<BuiltProgram> built_;
  // The log of the build of `name` (files or "source"): kept, and shown under $RUNNEL_KERNEL_LOG.
  void keep_build_log(const std::string& name, const std::string& log);
};

// The text of an embedded source file, prefixed by a #line directive with its path.
std::string embedded_source(const std::string& path);

// A readable name for an OpenCL error code, e.g. "CL_OUT_OF_RESOURCES".
const char* cl_error_name(int code);

}  // namespace runnel
