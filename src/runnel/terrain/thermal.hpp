// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/sim/parameters.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

struct ThermalSettings {
  double talus_angle_deg = 40.0;
  double rate = 0.5;          // c: fraction of the excess moved per pass
  bool height_aware = false;  // talus threshold rising with height (hardness)
  double hardness = 1.0;      // height-aware: threshold × (1 + hardness · normalised height)
  static ThermalSettings from(const Parameters& params);  // the thermal.* parameters
};

// Host side of cl/thermal.cl: one talus relaxation pass over the device terrain's fixed-point
// heights (two kernels: outflows, then gather), exact in volume. Refreshes the float view.
class ThermalRelaxation {
 public:
  ThermalRelaxation(ComputeContext& compute, DeviceTerrain& terrain,
                    const ThermalSettings& settings);
  void relax();

 private:
  ComputeContext& compute_;
  DeviceTerrain& terrain_;
  ThermalSettings settings_;
  cl::Buffer outflow_;
  Kernel outflow_kernel_, gather_kernel_;
};

}  // namespace runnel
