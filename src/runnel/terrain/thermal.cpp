// SPDX-License-Identifier: MIT
#include "runnel/terrain/thermal.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/compute/launch.hpp"

namespace runnel {

ThermalSettings ThermalSettings::from(const Parameters& p) {
  ThermalSettings s;
  s.talus_angle_deg = p.real("thermal.talus_angle");
  s.rate = p.real("thermal.rate");
  s.height_aware = p.boolean("thermal.height_aware");
  s.hardness = p.real("thermal.hardness");
  return s;
}

ThermalRelaxation::ThermalRelaxation(ComputeContext& compute, DeviceTerrain& terrain,
                                     const ThermalSettings& settings)
    : compute_(compute),
      terrain_(terrain),
      settings_(settings),
      outflow_(compute.context(), CL_MEM_READ_WRITE,
               static_cast<std::size_t>(terrain.nx()) * terrain.ny() * 4 * sizeof(cl_long)) {
  cl::Program& program = compute.program({"cl/thermal.cl"});
  outflow_kernel_ = cl::Kernel(program, "thermal_outflow");
  gather_kernel_ = cl::Kernel(program, "thermal_gather");
}

void ThermalRelaxation::relax() {
  const int nx = terrain_.nx(), ny = terrain_.ny();
  const double threshold_m = terrain_.cell() * std::tan(settings_.talus_angle_deg * M_PI / 180.0);
  const cl_long talus = static_cast<cl_long>(std::llround(threshold_m / terrain_.quantum()));
  cl_long h_min = 0, h_range = 0;
  if (settings_.height_aware) {
    const auto fixed = terrain_.download_fixed();
    const auto [lo, hi] = std::minmax_element(fixed.begin(), fixed.end());
    h_min = *lo;
    h_range = *hi - *lo;
  }
  set_args(outflow_kernel_, terrain_.height_fixed(), outflow_, nx, ny, talus,
           static_cast<float>(settings_.rate), static_cast<cl_int>(settings_.height_aware),
           static_cast<float>(settings_.hardness), h_min, h_range);
  compute_.profiler().launch(outflow_kernel_, round_up_work(static_cast<std::size_t>(nx) * ny),
                             "thermal_outflow");
  set_args(gather_kernel_, terrain_.height_fixed(), outflow_, nx, ny);
  compute_.profiler().launch(gather_kernel_, round_up_work(static_cast<std::size_t>(nx) * ny),
                             "thermal_gather");
  terrain_.apply();
}

}  // namespace runnel
