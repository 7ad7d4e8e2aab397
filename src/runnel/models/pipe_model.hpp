// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/sim/parameters.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

struct PipeSettings {
  double rain = 0.01;         // m/s of water on every cell
  double area = 1.0;          // A, pipe cross-section, m²
  double gravity = 9.81;      // m/s²
  double capacity = 0.05;     // K_c, s (capacity = K_c · sin α · |v|, in m of height)
  double dissolve = 0.1;      // K_s, fraction of the free capacity dissolved per step
  double deposit = 0.1;       // K_d, fraction of the excess deposited per step
  double evaporation = 0.05;  // K_e, 1/s
  double min_tilt = 0.05;     // smallest sin α in the capacity
  double cfl = 0.25;
  double dt_max = 0.05;  // s
  bool closed = false;   // closed edges; default outflow
  static PipeSettings from(const Parameters& params);
  std::string build_options() const;
};

// Erosion_Mei2007: host side of cl/models/pipe.cl. advance() takes one adaptive step,
// Δt = min(dt_max, CFL · l / (sqrt(g · d_max) + |v|_max)); terrain + suspended sediment + outflow
// are conserved exactly (integer quanta, mass-conserving upwind transport).
class PipeModel {
 public:
  PipeModel(ComputeContext& compute, DeviceTerrain& terrain, const PipeSettings& settings);
  void advance();
  double dt() const { return dt_; }
  double time() const { return time_; }
  long long suspended_quanta();
  long long outflow_quanta();
  std::vector<float> depth();

 private:
  ComputeContext& compute_;
  DeviceTerrain& terrain_;
  PipeSettings settings_;
  double dt_ = 0, time_ = 0;
  cl::Buffer depth_, flux_, velocity_, previous_depth_, sediment_[2], stats_, outflow_;
  int current_ = 0;
  cl::Kernel flux_kernel_, water_kernel_, erode_kernel_, transport_kernel_, stats_kernel_;
};

}  // namespace runnel
