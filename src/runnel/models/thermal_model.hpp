// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/models/grid_model.hpp"
#include "runnel/terrain/thermal.hpp"

namespace runnel {

// Erosion_Musgrave1989: talus relaxation (Musgrave, Kolb & Mace 1989; Olsen 2004), constant or
// height-aware (Fritz 2016). One step is one relaxation pass of cl/thermal.cl
// (ThermalRelaxation, the same pass the SPH model runs every thermal.interval seconds). No water,
// no rain; volume is exact (integer quanta, closed edges).
class ThermalModel final : public GridModel {
 public:
  static const ModelInfo& model_info();
  ThermalModel(ComputeContext& compute, const Parameters& params, const Heightmap& terrain);
  const ModelInfo& info() const override { return model_info(); }
  JsonObject diagnostics() override;

 protected:
  double take_step() override;
  double scratch_bytes() const override { return relaxation_.device_bytes(); }

 private:
  ThermalSettings settings_;
  ThermalRelaxation relaxation_;
};

}  // namespace runnel
