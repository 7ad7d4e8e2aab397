// SPDX-License-Identifier: MIT
#include "runnel/models/thermal_model.hpp"

namespace runnel {

const ModelInfo& ThermalModel::model_info() {
  static const ModelInfo info{
      "thermal",
      "Erosion_Musgrave1989",
      "F. K. Musgrave, C. E. Kolb, R. S. Mace: The synthesis and rendering of eroded fractal "
      "terrains, SIGGRAPH 1989",
      "thermal",
      ModelClock::kIterations,
      false,
      {{kTopographicElevation, FieldIntent::kInOut}},
      {},
      72};
  return info;
}

ThermalModel::ThermalModel(ComputeContext& compute, const Parameters& params,
                           const Heightmap& terrain)
    : GridModel(compute, params, terrain),
      settings_(ThermalSettings::from(params)),
      relaxation_(compute, state_.terrain(), settings_, bed()) {}

double ThermalModel::take_step() {
  relaxation_.relax();
  return 1.0;
}

JsonObject ThermalModel::diagnostics() {
  return JsonObject()
      .add("talus_angle_deg", settings_.talus_angle_deg)
      .add("height_aware", settings_.height_aware);
}

}  // namespace runnel
