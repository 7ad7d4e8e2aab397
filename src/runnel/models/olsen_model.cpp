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

const ModelInfo& OlsenModel::model_info() {
  static const ModelInfo info{
      "olsen",
      "Erosion_Olsen2004",
      "J. Olsen: Realtime procedural terrain generation, University of Southern Denmark, 2004",
      "olsen",
      ModelClock::kIterations,
      true,
      {{kTopographicElevation, FieldIntent::kInOut},
       {kSurfaceWaterDepth, FieldIntent::kOut},
       {kSedimentSuspended, FieldIntent::kOut}}};
  return info;
}

OlsenModel::OlsenModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain)
    : GridModel(compute, params, terrain),
      settings_(OlsenSettings::from(params)),
      water_(state_.field(kSurfaceWaterDepth)),
      sediment_(state_.field(kSedimentSuspended)) {
  const std::size_t n = state_.vertices();
  out_water_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, 4 * n * sizeof(float));
  out_sediment_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, 4 * n * sizeof(cl_long));
  const OlsenSettings& s = settings_;
  const std::string options =
      float_define("OLSEN_RAIN", s.rain) + float_define("OLSEN_SOLUBILITY", s.solubility) +
      float_define("OLSEN_EVAPORATION", s.evaporation) + float_define("OLSEN_CAPACITY", s.capacity);
  cl::Program& program = compute.program({"cl/models/olsen.cl"}, options);
  dissolve_ = Kernel(compute, program, "olsen_dissolve");
  outflow_ = Kernel(compute, program, "olsen_outflow");
  gather_ = Kernel(compute, program, "olsen_gather");
  settle_ = Kernel(compute, program, "olsen_settle");
}

double OlsenModel::take_step() {
  DeviceTerrain& terrain = state_.terrain();
  const int nx = terrain.nx(), ny = terrain.ny(), n = nx * ny;
  const float q = static_cast<float>(terrain.quantum());
  const std::size_t work = round_up_work(static_cast<std::size_t>(n));
  cl::Buffer &water = state_.buffer(water_), &sediment = state_.buffer(sediment_);
  for (Kernel* k : {&dissolve_, &settle_}) {
    k->set("height", terrain.height_fixed()).set("water", water).set("sediment", sediment);
    k->set("n", n).set("quantum", q);
  }
  outflow_.set("height", terrain.height_fixed()).set("water", water).set("sediment", sediment);
  outflow_.set("quantum", q);
  gather_.set("water", water).set("sediment", sediment);
  for (Kernel* k : {&outflow_, &gather_}) {
    k->set("out_water", out_water_).set("out_sediment", out_sediment_).set("nx", nx).set("ny", ny);
  }
  for (Kernel* k : {&dissolve_, &outflow_, &gather_, &settle_}) k->launch(work);
  terrain.apply();
  return 1.0;
}

double OlsenModel::rain_volume() {
  const double cell = state_.terrain().cell();
  return settings_.rain * static_cast<double>(state_.vertices()) * cell * cell *
         static_cast<double>(steps());
}

JsonObject OlsenModel::diagnostics() {
  return JsonObject().add("water_volume_m3", water_volume());
}

}  // namespace runnel
