// SPDX-License-Identifier: MIT
#include "runnel/models/fields.hpp"

#include <cmath>
#include <stdexcept>

namespace runnel {

const std::vector<FieldDescription>& field_dictionary() {
  using L = FieldLocation;
  using T = FieldType;
  // clang-format off
  static const std::vector<FieldDescription> fields = {
      {kTopographicElevation, L::kVertex, T::kInt64, 1, "height quanta", "terrain height as an exact count of the height quantum (erosion.height_quantum, m)"},
      {kSurfaceWaterDepth, L::kVertex, T::kFloat32, 1, "m", "depth of the water standing on the vertex's cell"},
      {kSedimentSuspended, L::kVertex, T::kInt64, 1, "height quanta", "sediment carried by the water over the cell, as a count of the height quantum"},
      {kSurfaceWaterOutflux, L::kVertex, T::kFloat32, 4, "m^3/s", "virtual-pipe outflow to the left, right, top (-z) and bottom (+z) neighbours"},
      {kSurfaceWaterVelocity, L::kVertex, T::kFloat32, 2, "m/s", "depth-averaged water velocity (x, z)"},
      {"ground__sediment_thickness", L::kVertex, T::kInt64, 1, "height quanta", "loose sediment on the rock (what was eroded and deposited), the first to be eroded again (docs/layers.md)"},
      {"ground__contact_elevation", L::kVertex, T::kInt64, 0, "height quanta", "the strata's contacts, top first: contact 0 the initial surface, stratum l between contacts l and l + 1, the bedrock below the last (L + 1 components)"},
      {"ground__erodibility_mask", L::kVertex, T::kFloat32, 1, "1", "the erodibility mask as painted in runnel-viewer (hardness × frozen: 0 never erodes); only in checkpoints of a session that painted it"},
      {"ground__rain_mask", L::kVertex, T::kFloat32, 1, "1", "the rain mask as painted in runnel-viewer (the fraction of the scenario's rain falling at the vertex); only in checkpoints of a session that painted it"},
      {"ground__stratum_thickness", L::kVertex, T::kInt64, 0, "height quanta", "the thickness left of each stratum above the rock surface's fall (L components; written for readers, derived on restart)"},
      {"particle__position", L::kParticle, T::kFloat32, 3, "m", "SPH particle position (x, y, z)"},
      {"particle__velocity", L::kParticle, T::kFloat32, 3, "m/s", "SPH particle velocity"},
      {"particle__density", L::kParticle, T::kFloat32, 1, "kg/m^3", "SPH particle density"},
      {"particle__sediment", L::kParticle, T::kInt32, 1, "volume quanta", "sediment a particle carries, count of height quantum x cell^2"},
      {"particle__age", L::kParticle, T::kFloat32, 1, "s", "time since the particle fell"},
      {"particle__lifespan", L::kParticle, T::kFloat32, 1, "s", "age at which the particle evaporates"},
      {"particle__contacts", L::kParticle, T::kUint32, 1, "1", "erosion events so far (acidity model)"},
      {"particle__id", L::kParticle, T::kUint32, 1, "1", "stable particle id"},
  };
  // clang-format on
  return fields;
}

const FieldDescription& field_description(const std::string& name) {
  for (const auto& f : field_dictionary())
    if (f.name == name) return f;
  throw std::out_of_range("no field named " + name + " in the field dictionary");
}

std::string field_value_problem(const std::string& name, float value) {
  if (!std::isfinite(value)) return "not a finite number";
  const bool not_negative = name == kSurfaceWaterDepth || name == kSurfaceWaterOutflux ||
                            name == "ground__erodibility_mask" || name == "ground__rain_mask";
  if (not_negative && value < 0) return "below 0";
  if (name == "ground__rain_mask" && value > 1) return "above 1 (a fraction of the rain)";
  return "";
}

const char* to_string(FieldLocation location) {
  return location == FieldLocation::kVertex ? "vertex" : "particle";
}

const char* to_string(FieldType type) {
  switch (type) {
    case FieldType::kFloat32:
      return "float32";
    case FieldType::kInt32:
      return "int32";
    case FieldType::kUint32:
      return "uint32";
    case FieldType::kInt64:
      return "int64";
  }
  return "?";
}

const char* to_string(FieldIntent intent) {
  switch (intent) {
    case FieldIntent::kIn:
      return "in";
    case FieldIntent::kOut:
      return "out";
    case FieldIntent::kInOut:
      return "inout";
  }
  return "?";
}

}  // namespace runnel
