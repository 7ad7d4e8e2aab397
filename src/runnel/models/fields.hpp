// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

// The field dictionary: every quantity a model reads or writes, described once (name, location,
// type, unit, meaning) in Landlab's naming style, and listed in docs/fields.md. Models refer to
// fields by these names; a test fails when a model declares a field the dictionary lacks.
namespace runnel {

enum class FieldLocation { kVertex, kParticle };
enum class FieldType { kFloat32, kInt32, kUint32, kInt64 };
enum class FieldIntent { kIn, kOut, kInOut };

struct FieldDescription {
  std::string name;
  FieldLocation location;
  FieldType type;
  int components;  // values per vertex or particle; 0: one per stratum of the run's layer stack
  std::string unit;
  std::string doc;
};

// How one model uses a dictionary field.
struct FieldUse {
  std::string name;
  FieldIntent intent;
  bool optional = false;
};

const std::vector<FieldDescription>& field_dictionary();
// The dictionary entry of `name`; throws std::out_of_range for a name not in it.
const FieldDescription& field_description(const std::string& name);

// Why `value` cannot be stored in field `name` ("" when it can): every value finite; depths,
// fluxes and masks not negative; a rain mask at most 1.
std::string field_value_problem(const std::string& name, float value);

const char* to_string(FieldLocation location);
const char* to_string(FieldType type);
const char* to_string(FieldIntent intent);

// The shared field names.
inline constexpr const char* kTopographicElevation = "topographic__elevation";
inline constexpr const char* kSurfaceWaterDepth = "surface_water__depth";
inline constexpr const char* kSedimentSuspended = "sediment__suspended";
inline constexpr const char* kSurfaceWaterOutflux = "surface_water__outflux";
inline constexpr const char* kSurfaceWaterVelocity = "surface_water__velocity";

}  // namespace runnel
