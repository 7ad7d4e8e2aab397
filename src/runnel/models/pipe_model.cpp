// SPDX-License-Identifier: MIT
#include "runnel/models/pipe_model.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"

namespace runnel {
namespace {
constexpr int kStatBlocks = 1024;
}

PipeSettings PipeSettings::from(const Parameters& p) {
  PipeSettings s;
  s.rain = p.real("pipe.rain");
  s.area = p.real("pipe.area");
  s.gravity = p.real("pipe.gravity");
  s.capacity = p.real("pipe.capacity");
  s.dissolve = p.real("pipe.dissolve");
  s.deposit = p.real("pipe.deposit");
  s.evaporation = p.real("pipe.evaporation");
  s.min_tilt = p.real("pipe.min_tilt");
  s.cfl = p.real("pipe.cfl");
  s.dt_max = p.real("pipe.dt_max");
  s.closed = p.text("pipe.edges") == "closed";
  return s;
}

std::string PipeSettings::build_options() const {
  return float_define("PIPE_RAIN", rain) + float_define("PIPE_AREA", area) +
         float_define("PIPE_GRAVITY", gravity) + float_define("PIPE_CAPACITY", capacity) +
         float_define("PIPE_DISSOLVE", dissolve) + float_define("PIPE_DEPOSIT", deposit) +
         float_define("PIPE_EVAPORATION", evaporation) + float_define("PIPE_MIN_TILT", min_tilt) +
         " -DPIPE_CLOSED=" + (closed ? "1" : "0");
}

PipeModel::PipeModel(ComputeContext& compute, DeviceTerrain& terrain, const PipeSettings& settings)
    : compute_(compute), terrain_(terrain), settings_(settings), dt_(settings.dt_max) {
  const std::size_t n = static_cast<std::size_t>(terrain.nx()) * terrain.ny();
  auto& ctx = compute.context();
  depth_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
  flux_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * n * sizeof(float));
  velocity_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 2 * n * sizeof(float));
  previous_depth_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
  for (auto& s : sediment_) s = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(cl_long));
  stats_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 2 * kStatBlocks * sizeof(float));
  outflow_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, sizeof(cl_long));
  auto& q = compute.queue();
  const float zero = 0.0f;
  const cl_long zero_long = 0;
  q.enqueueFillBuffer(depth_, zero, 0, n * sizeof(float));
  q.enqueueFillBuffer(flux_, zero, 0, 4 * n * sizeof(float));
  q.enqueueFillBuffer(velocity_, zero, 0, 2 * n * sizeof(float));
  q.enqueueFillBuffer(sediment_[0], zero_long, 0, n * sizeof(cl_long));
  q.enqueueFillBuffer(outflow_, zero_long, 0, sizeof(cl_long));
  cl::Program& program = compute.program({"cl/models/pipe.cl"}, settings.build_options());
  flux_kernel_ = cl::Kernel(program, "pipe_flux");
  water_kernel_ = cl::Kernel(program, "pipe_water");
  erode_kernel_ = cl::Kernel(program, "pipe_erode");
  transport_kernel_ = cl::Kernel(program, "pipe_transport");
  stats_kernel_ = cl::Kernel(program, "pipe_stats");
}

void PipeModel::advance() {
  const int nx = terrain_.nx(), ny = terrain_.ny(), n = nx * ny;
  const float q = static_cast<float>(terrain_.quantum()), cell = terrain_.cell(),
              dt = static_cast<float>(dt_);
  const std::size_t work = round_up_work(static_cast<std::size_t>(n));
  auto& prof = compute_.profiler();
  set_args(flux_kernel_, terrain_.height_fixed(), depth_, flux_, nx, ny, q, cell, dt);
  prof.launch(flux_kernel_, work, "pipe_flux");
  set_args(water_kernel_, depth_, flux_, velocity_, previous_depth_, nx, ny, cell, dt);
  prof.launch(water_kernel_, work, "pipe_water");
  set_args(erode_kernel_, terrain_.height_fixed(), terrain_.height(), sediment_[current_], depth_,
           velocity_, nx, ny, q, cell, dt);
  prof.launch(erode_kernel_, work, "pipe_erode");
  set_args(transport_kernel_, sediment_[current_], sediment_[1 - current_], flux_, previous_depth_,
           nx, ny, cell, dt, outflow_);
  prof.launch(transport_kernel_, work, "pipe_transport");
  current_ = 1 - current_;
  terrain_.apply();
  time_ += dt_;
  // The next step: the CFL limit of the shallow-water waves and the flow (Fritz 2016 saw
  // oscillation and overflow with steps that violate it).
  const int chunk = (n + kStatBlocks - 1) / kStatBlocks;
  set_args(stats_kernel_, depth_, velocity_, n, chunk, stats_);
  prof.launch(stats_kernel_, kStatBlocks, "pipe_stats");
  std::vector<float> stats(2 * kStatBlocks);
  compute_.queue().enqueueReadBuffer(stats_, CL_TRUE, 0, stats.size() * sizeof(float),
                                     stats.data());
  double d_max = 0, v_max = 0;
  for (int b = 0; b < kStatBlocks; ++b) {
    d_max = std::max(d_max, static_cast<double>(stats[2 * b]));
    v_max = std::max(v_max, static_cast<double>(stats[2 * b + 1]));
  }
  if (!std::isfinite(d_max) || !std::isfinite(v_max)) {
    throw runtime_error("pipe model at t = " + std::to_string(time_) +
                        " s: water depth or velocity is not finite");
  }
  dt_ = std::min(settings_.dt_max,
                 settings_.cfl * cell / (std::sqrt(settings_.gravity * d_max) + v_max + 1e-9));
}

long long PipeModel::suspended_quanta() {
  std::vector<cl_long> s(static_cast<std::size_t>(terrain_.nx()) * terrain_.ny());
  compute_.queue().enqueueReadBuffer(sediment_[current_], CL_TRUE, 0, s.size() * sizeof(cl_long),
                                     s.data());
  long long sum = 0;
  for (auto v : s) sum += v;
  return sum;
}

long long PipeModel::outflow_quanta() {
  cl_long v = 0;
  compute_.queue().enqueueReadBuffer(outflow_, CL_TRUE, 0, sizeof(v), &v);
  return v;
}

std::vector<float> PipeModel::depth() {
  std::vector<float> d(static_cast<std::size_t>(terrain_.nx()) * terrain_.ny());
  compute_.queue().enqueueReadBuffer(depth_, CL_TRUE, 0, d.size() * sizeof(float), d.data());
  return d;
}

}  // namespace runnel
