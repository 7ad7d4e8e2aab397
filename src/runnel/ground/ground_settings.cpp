// SPDX-License-Identifier: MIT
#include "runnel/ground/ground_settings.hpp"

#include "runnel/core/parameter_groups.hpp"
#include "runnel/core/settings_table.hpp"

namespace runnel {
namespace {

using G = GroundSettings;
// clang-format off
const SettingsTable<GroundSettings> kGroundTable = {
      // ground: what the terrain is made of (with the [[layers]] strata; docs/layers.md)
      {"ground.bedrock_name", "\"bedrock\"", "", 0, 0, {}, "name of the rock below the last stratum", &G::bedrock_name},
      {"ground.bedrock_erodibility", "1", "1", 0, 1e6, {}, "factor on every model's erosion rate where the bedrock is exposed", &G::bedrock_erodibility},
      {"ground.bedrock_talus_angle", "0", "deg", 0, 89, {}, "the bedrock's talus angle; 0: thermal.talus_angle", &G::bedrock_talus_angle},
      {"ground.bedrock_density", "2700", "kg/m3", 1, 1e5, {}, "the bedrock's bulk density (metrics.json)", &G::bedrock_density},
      {"ground.sediment_erodibility", "1", "1", 0, 1e6, {}, "factor on the erosion rate where loose sediment (what was eroded and deposited) lies on top", &G::sediment_erodibility},
      {"ground.sediment_talus_angle", "0", "deg", 0, 89, {}, "the loose sediment's talus angle; 0: thermal.talus_angle", &G::sediment_talus_angle},
      {"ground.sediment_density", "1600", "kg/m3", 1, 1e5, {}, "the loose sediment's bulk density (metrics.json)", &G::sediment_density},
      {"ground.active_layer", "0.01", "m", 1e-9, 1e6, {}, "active layer (Hirano 1971): the bed erodes as a blend of its loose sediment and the rock below, by the share of this thickness the sediment fills; the maps show the sediment where it fills half of it", &G::active_layer},
      {"ground.hardness_mask", "\"\"", "", 0, 0, {}, "raster of a factor ≥ 0 on the erodibility per vertex (any terrain format), relative to the scenario; empty: none", &G::hardness_mask},
      {"ground.rain_mask", "\"\"", "", 0, 0, {}, "raster of the fraction (0 to 1) of the rain that falls at each vertex, for every model with rain; empty: rain everywhere", &G::rain_mask},
      {"ground.frozen_mask", "\"\"", "", 0, 0, {}, "raster; where it is not 0 the ground is frozen and nothing erodes; empty: none", &G::frozen_mask},
};
// clang-format on

}  // namespace

std::vector<ParamSpec> ground_parameters() {
  return settings_specs(kGroundTable);
}

GroundSettings GroundSettings::from(const Parameters& p) {
  return read_settings(p, kGroundTable);
}

bool has_ground(const Parameters& params) {
  return !params.layers().empty() || !params.text("ground.hardness_mask").empty() ||
         !params.text("ground.frozen_mask").empty();
}

bool has_rain_mask(const Parameters& params) {
  return !params.text("ground.rain_mask").empty();
}

std::string ground_defines(const Parameters& params) {
  return std::string(" -DGROUND=") + (has_ground(params) ? "1" : "0") +
         " -DRAIN_MASK=" + (has_rain_mask(params) ? "1" : "0");
}

}  // namespace runnel
