// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/sim/parameters.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

struct OlsenSettings {
  double rain = 0.01;        // K_r, m of water per iteration
  double solubility = 0.01;  // K_s, fraction of the water depth dissolved per iteration
  double evaporation = 0.5;  // K_e, fraction of the water evaporating per iteration
  double capacity = 0.01;    // K_c, sediment capacity per unit water depth
  static OlsenSettings from(const Parameters& params);
};

// Erosion_Olsen2004: host side of cl/models/olsen.cl. One advance() is one iteration over every
// cell; terrain + suspended sediment is conserved exactly (integer quanta, closed edges).
class OlsenModel {
 public:
  OlsenModel(ComputeContext& compute, DeviceTerrain& terrain, const OlsenSettings& settings);
  void advance();
  // Suspended sediment over all cells, in height quanta.
  long long suspended_quanta();
  std::vector<float> water();

 private:
  ComputeContext& compute_;
  DeviceTerrain& terrain_;
  cl::Buffer water_, sediment_, out_water_, out_sediment_;
  cl::Kernel dissolve_, outflow_, gather_, settle_;
};

}  // namespace runnel
