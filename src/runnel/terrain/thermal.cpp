// SPDX-License-Identifier: MIT
#include "runnel/terrain/thermal.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/buffer_bytes.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/settings_table.hpp"

namespace runnel {

namespace {

// clang-format off
const SettingsTable<ThermalSettings> kThermalTable = {
      // thermal: talus relaxation during a run
      {"thermal.interval", "0.5", "s", 0, 1e9, {}, "SPH runs: relax slopes steeper than the talus angle every this many simulated seconds; 0: off", &ThermalSettings::interval},
      {"thermal.talus_angle", "40", "deg", 0, 89, {}, "talus angle", &ThermalSettings::talus_angle_deg},
      {"thermal.rate", "0.5", "1", 0, 1, {}, "c, the fraction of the excess moved per relaxation", &ThermalSettings::rate},
      {"thermal.height_aware", "false", "", 0, 0, {}, "height-aware talus (Fritz 2016): the threshold rises with height, keeping peaks sharp", &ThermalSettings::height_aware},
      {"thermal.hardness", "1", "1", 0, 100, {}, "height-aware: threshold × (1 + hardness · normalised height)", &ThermalSettings::hardness},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> thermal_parameters() {
  return settings_specs(kThermalTable);
}

std::int64_t talus_threshold_quanta(double cell, double angle_deg, double quantum) {
  return std::llround(cell * std::tan(angle_deg * M_PI / 180.0) / quantum);
}

ThermalSettings ThermalSettings::from(const Parameters& p) {
  return read_settings(p, kThermalTable);
}

ThermalRelaxation::ThermalRelaxation(ComputeContext& compute, DeviceTerrain& terrain,
                                     const ThermalSettings& settings, const BedFields* bed)
    : terrain_(terrain),
      settings_(settings),
      outflow_(compute.context(), CL_MEM_READ_WRITE,
               static_cast<std::size_t>(terrain.nx()) * terrain.ny() * 4 * sizeof(cl_long)) {
  cl::Program& program =
      compute.program({"cl/common.cl", "cl/thermal.cl"}, bed ? " -DGROUND=1" : "");
  outflow_kernel_ = Kernel(compute, program, "thermal_outflow");
  placeholder_ = placeholder_buffer(compute);
  bind_detachment(outflow_kernel_, bed, placeholder_);
  outflow_kernel_.set("talus_field", bed ? bed->talus : placeholder_);
  gather_kernel_ = Kernel(compute, program, "thermal_gather");
}

double ThermalRelaxation::device_bytes() const {
  return buffer_bytes({&outflow_, &placeholder_});
}

void ThermalRelaxation::relax() {
  const int nx = terrain_.nx(), ny = terrain_.ny();
  const cl_long talus =
      talus_threshold_quanta(terrain_.cell(), settings_.talus_angle_deg, terrain_.quantum());
  cl_long h_min = 0, h_range = 0;
  if (settings_.height_aware) {
    const auto fixed = terrain_.download_fixed();
    const auto [lo, hi] = std::minmax_element(fixed.begin(), fixed.end());
    h_min = *lo;
    h_range = *hi - *lo;
  }
  const std::size_t cells = round_up_work(static_cast<std::size_t>(nx) * ny);
  for (Kernel* k : {&outflow_kernel_, &gather_kernel_}) {
    k->set("height", terrain_.height_fixed()).set("outflow", outflow_).set("nx", nx).set("ny", ny);
  }
  outflow_kernel_.set("talus", talus)
      .set("rate", static_cast<float>(settings_.rate))
      .set("height_aware", static_cast<cl_int>(settings_.height_aware))
      .set("hardness", static_cast<float>(settings_.hardness))
      .set("h_min", h_min)
      .set("h_range", h_range)
      .launch(cells);
  gather_kernel_.launch(cells);
  terrain_.apply();
}

}  // namespace runnel
