// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/models/grid_model.hpp"

namespace runnel {

struct OlsenSettings {
  // The olsen.* parameters (defaults, units, meaning: the table in olsen_model.cpp).
  double rain;         // K_r, m of water per iteration
  double solubility;   // K_s, fraction of the water depth dissolved per iteration
  double evaporation;  // K_e, fraction of the water evaporating per iteration
  double capacity;     // K_c, sediment capacity per unit water depth
  static OlsenSettings from(const Parameters& params);
};

// The most quanta of a cell's suspended sediment one outflow pass shares among its lower neighbours
// (olsen.cl: the pass computes in 32 bits); a cell holding more keeps the rest for later passes.
inline constexpr long long kOlsenSendable = 1LL << 30;

// Erosion_Olsen2004: cellular-automaton hydraulic erosion (Olsen 2004, as used by Fritz 2016), host
// side of cl/models/olsen.cl. One step is one iteration over every cell; terrain + suspended
// sediment is conserved exactly (integer quanta, closed edges).
class OlsenModel final : public GridModel {
 public:
  static const ModelInfo& model_info();
  OlsenModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);
  const ModelInfo& info() const override { return model_info(); }

  std::vector<float> water() { return state_.download_float(kSurfaceWaterDepth); }
  double rain_volume() override;
  double scenario_rain_rate() const override { return settings_.rain; }
  JsonObject diagnostics() override;

 protected:
  double take_step() override;
  double scratch_bytes() const override;

 private:
  OlsenSettings settings_;
  int water_, sediment_;  // GridState handles
  cl::Buffer out_water_, out_sediment_;
  cl::Buffer level_, sendable_;  // olsen_dissolve's 32-bit copies for olsen_outflow (olsen.cl)
  Kernel dissolve_, outflow_, gather_settle_;
};

}  // namespace runnel
