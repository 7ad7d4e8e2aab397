// SPDX-License-Identifier: MIT
#include "runnel/models/olsen_model.hpp"

#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"

namespace runnel {

OlsenSettings OlsenSettings::from(const Parameters& p) {
  OlsenSettings s;
  s.rain = p.real("olsen.rain");
  s.solubility = p.real("olsen.solubility");
  s.evaporation = p.real("olsen.evaporation");
  s.capacity = p.real("olsen.capacity");
  return s;
}

OlsenModel::OlsenModel(ComputeContext& compute, DeviceTerrain& terrain, const OlsenSettings& s)
    : compute_(compute), terrain_(terrain) {
  const std::size_t n = static_cast<std::size_t>(terrain.nx()) * terrain.ny();
  auto& ctx = compute.context();
  water_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(float));
  sediment_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, n * sizeof(cl_long));
  out_water_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * n * sizeof(float));
  out_sediment_ = cl::Buffer(ctx, CL_MEM_READ_WRITE, 4 * n * sizeof(cl_long));
  const float zero = 0.0f;
  const cl_long zero_long = 0;
  compute.queue().enqueueFillBuffer(water_, zero, 0, n * sizeof(float));
  compute.queue().enqueueFillBuffer(sediment_, zero_long, 0, n * sizeof(cl_long));
  const std::string options =
      float_define("OLSEN_RAIN", s.rain) + float_define("OLSEN_SOLUBILITY", s.solubility) +
      float_define("OLSEN_EVAPORATION", s.evaporation) + float_define("OLSEN_CAPACITY", s.capacity);
  cl::Program& program = compute.program({"cl/models/olsen.cl"}, options);
  dissolve_ = cl::Kernel(program, "olsen_dissolve");
  outflow_ = cl::Kernel(program, "olsen_outflow");
  gather_ = cl::Kernel(program, "olsen_gather");
  settle_ = cl::Kernel(program, "olsen_settle");
}

void OlsenModel::advance() {
  const int nx = terrain_.nx(), ny = terrain_.ny(), n = nx * ny;
  const float q = static_cast<float>(terrain_.quantum());
  const std::size_t work = round_up_work(static_cast<std::size_t>(n));
  auto& prof = compute_.profiler();
  set_args(dissolve_, terrain_.height_fixed(), water_, sediment_, n, q);
  prof.launch(dissolve_, work, "olsen_dissolve");
  set_args(outflow_, terrain_.height_fixed(), water_, sediment_, out_water_, out_sediment_, nx, ny,
           q);
  prof.launch(outflow_, work, "olsen_outflow");
  set_args(gather_, water_, sediment_, out_water_, out_sediment_, nx, ny);
  prof.launch(gather_, work, "olsen_gather");
  set_args(settle_, terrain_.height_fixed(), water_, sediment_, n, q);
  prof.launch(settle_, work, "olsen_settle");
  terrain_.apply();
}

long long OlsenModel::suspended_quanta() {
  std::vector<cl_long> s(static_cast<std::size_t>(terrain_.nx()) * terrain_.ny());
  compute_.queue().enqueueReadBuffer(sediment_, CL_TRUE, 0, s.size() * sizeof(cl_long), s.data());
  long long sum = 0;
  for (auto v : s) sum += v;
  return sum;
}

std::vector<float> OlsenModel::water() {
  std::vector<float> w(static_cast<std::size_t>(terrain_.nx()) * terrain_.ny());
  compute_.queue().enqueueReadBuffer(water_, CL_TRUE, 0, w.size() * sizeof(float), w.data());
  return w;
}

}  // namespace runnel
