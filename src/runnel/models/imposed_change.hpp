// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/core/stored_field.hpp"

namespace runnel {

class DeviceTerrain;

inline constexpr const char* kImposedElevationChange = "ground__imposed_elevation_change";

// Heights a coupler set from outside the model (Model::set_elevation: Landlab's uplift or hillslope
// diffusion between storms, BMI's set_value of the elevation). The mass balance books them as an
// external source, exactly, in quanta, and per vertex, so that the eroded and deposited volumes
// stay what the model's own processes did.
class ImposedChange {
 public:
  // Replaces the terrain's heights with a coupler's (m, one a vertex), rounded to its quantum, and
  // books the change. Refused (an input error) for a run with a layer stack, whose strata cannot
  // tell what the change was made of; for the wrong count of heights; for a height not finite or
  // beyond the terrain's range of 2^53 quanta.
  void impose(DeviceTerrain& terrain, const std::vector<double>& metres, bool layered);
  // Books the step from `before` to `after` (fixed-point heights, the same size).
  void add(const std::vector<std::int64_t>& before, const std::vector<std::int64_t>& after);
  // Quanta imposed in all, and at each vertex (empty until something was imposed).
  long long total() const { return total_; }
  const std::vector<std::int64_t>& per_vertex() const { return per_vertex_; }
  // `reference` raised by what was imposed (the erosion maps' surface), quantum m a count.
  void raise(Heightmap& reference, double quantum) const;
  // Into a checkpoint's fields (only when something was imposed), and back.
  void store(std::vector<StoredField>& fields) const;
  void restore(const std::vector<StoredField>& fields);

 private:
  std::vector<std::int64_t> per_vertex_;
  long long total_ = 0;
};

// The terrain's exact heights in metres (count × quantum: exact for every count below 2^53); what
// ImposedChange::impose() is given back rounds to the same counts.
std::vector<double> heights_in_metres(DeviceTerrain& terrain);

}  // namespace runnel
