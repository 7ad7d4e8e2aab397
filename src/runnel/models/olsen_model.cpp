// SPDX-License-Identifier: MIT
#include "runnel/models/olsen_model.hpp"

#include "runnel/ground/ground_settings.hpp"

#include "runnel/compute/buffer_bytes.hpp"
#include "runnel/compute/build_options.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/settings_table.hpp"

namespace runnel {

namespace {

// clang-format off
const SettingsTable<OlsenSettings> kOlsenTable = {
      // olsen: cellular-automaton hydraulic erosion (Olsen 2004), per iteration
      {"olsen.rain", "0.01", "m", 0, 1e3, {}, "K_r, water added to every cell per iteration", &OlsenSettings::rain, "OLSEN_RAIN"},
      {"olsen.solubility", "0.01", "1", 0, 1, {}, "K_s, terrain dissolved per unit water depth", &OlsenSettings::solubility, "OLSEN_SOLUBILITY"},
      {"olsen.evaporation", "0.5", "1", 0, 1, {}, "K_e, fraction of the water evaporating per iteration", &OlsenSettings::evaporation, "OLSEN_EVAPORATION"},
      {"olsen.capacity", "0.01", "1", 0, 1e3, {}, "K_c, sediment capacity per unit water depth", &OlsenSettings::capacity, "OLSEN_CAPACITY"},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> olsen_parameters() {
  return settings_specs(kOlsenTable);
}

OlsenSettings OlsenSettings::from(const Parameters& p) {
  return read_settings(p, kOlsenTable);
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
       {kSedimentSuspended, FieldIntent::kOut}},
      {},
      96};
  return info;
}

OlsenModel::OlsenModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain)
    : GridModel(compute, params, terrain),
      settings_(OlsenSettings::from(params)),
      water_(state_.field(kSurfaceWaterDepth)),
      sediment_(state_.field(kSedimentSuspended)) {
  const std::size_t n = state_.vertices();
  // Four planes with a zero row before and after each (olsen_plane in olsen.cl).
  const std::size_t planes = 4 * (n + 2 * static_cast<std::size_t>(terrain.nx));
  out_water_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, planes * sizeof(float));
  out_sediment_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, planes * sizeof(cl_int));
  compute.queue().enqueueFillBuffer(out_water_, 0.0f, 0, planes * sizeof(float));
  compute.queue().enqueueFillBuffer(out_sediment_, cl_int{0}, 0, planes * sizeof(cl_int));
  level_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, n * sizeof(float));
  sendable_ = cl::Buffer(compute.context(), CL_MEM_READ_WRITE, n * sizeof(cl_int));
  const OlsenSettings& s = settings_;
  const std::string options = settings_defines(s, kOlsenTable) + ground_defines(params) +
                              " -DOLSEN_SENDABLE=" + std::to_string(kOlsenSendable) + "L";
  cl::Program& program = compute.program({"cl/common.cl", "cl/models/olsen.cl"}, options);
  dissolve_ = Kernel(compute, program, "olsen_dissolve");
  outflow_ = Kernel(compute, program, "olsen_outflow");
  gather_settle_ = Kernel(compute, program, "olsen_gather_settle");
  bind_detachment(dissolve_, bed(), placeholder_);
  dissolve_.set("rain_weight", rain_weight()).set("level", level_).set("sendable", sendable_);
  outflow_.set("level", level_).set("sendable", sendable_);
  start_standing_water(params);
}

double OlsenModel::scratch_bytes() const {
  return buffer_bytes({&out_water_, &out_sediment_, &level_, &sendable_});
}

double OlsenModel::take_step() {
  DeviceTerrain& terrain = state_.terrain();
  const int nx = terrain.nx(), ny = terrain.ny(), n = nx * ny;
  const float q = static_cast<float>(terrain.quantum());
  const std::size_t work = round_up_work(static_cast<std::size_t>(n));
  cl::Buffer &water = state_.buffer(water_), &sediment = state_.buffer(sediment_);
  for (Kernel* k : {&dissolve_, &gather_settle_}) {
    k->set("height", terrain.height_fixed()).set("sediment", sediment).set("quantum", q);
  }
  for (Kernel* k : {&dissolve_, &outflow_, &gather_settle_}) k->set("water", water);
  dissolve_.set("n", n).set("rain_on", rain_on());
  for (Kernel* k : {&outflow_, &gather_settle_}) {
    k->set("out_water", out_water_).set("out_sediment", out_sediment_).set("nx", nx).set("ny", ny);
  }
  for (Kernel* k : {&dissolve_, &outflow_, &gather_settle_}) k->launch(work);
  terrain.apply();
  return 1.0;
}

double OlsenModel::rain_volume() {
  return scenario_rain_volume() + painted_volume_;
}

JsonObject OlsenModel::diagnostics() {
  return JsonObject().add("water_volume_m3", water_volume());
}

}  // namespace runnel
