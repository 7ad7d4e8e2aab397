// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/core/parameters.hpp"
#include "runnel/terrain/bed_fields.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

struct ThermalSettings {
  // The thermal.* parameters (their defaults, units and meaning: the table in thermal.cpp).
  double interval;         // s between relaxations in SPH runs; 0: off
  double talus_angle_deg;  // deg
  double rate;             // c: fraction of the excess moved per pass
  bool height_aware;       // talus threshold rising with height (hardness)
  double hardness;         // height-aware: threshold × (1 + hardness · normalised height)
  static ThermalSettings from(const Parameters& params);  // the thermal.* parameters
};

// The talus threshold cell·tan(angle) in counts of the height quantum, as the kernels compare it.
std::int64_t talus_threshold_quanta(double cell, double angle_deg, double quantum);

// Host side of cl/thermal.cl: one talus relaxation pass over the device terrain's fixed-point
// heights (two kernels: outflows, then gather), exact in volume. Refreshes the float view.
class ThermalRelaxation {
 public:
  // With a ground, each vertex's talus angle and rate are its exposed material's.
  ThermalRelaxation(ComputeContext& compute, DeviceTerrain& terrain,
                    const ThermalSettings& settings, const BedFields* bed = nullptr);
  void relax();
  // What its buffers hold on the device (the four outflow planes).
  double device_bytes() const;

 private:
  DeviceTerrain& terrain_;
  ThermalSettings settings_;
  cl::Buffer outflow_, placeholder_;
  Kernel outflow_kernel_, gather_kernel_;
};

}  // namespace runnel
