// SPDX-License-Identifier: MIT
#include "runnel/models/imposed_change.hpp"

#include <cmath>

#include "runnel/core/error.hpp"
#include "runnel/terrain/device_terrain.hpp"

namespace runnel {

namespace {

std::vector<std::int64_t> heights_in_quanta(const std::vector<double>& metres, double quantum,
                                            std::size_t vertices, const std::string& what) {
  if (metres.size() != vertices)
    throw input_error(what + ": " + std::to_string(metres.size()) + " values for " +
                      std::to_string(vertices) + " vertices");
  const double limit = static_cast<double>(kMaxHeightQuanta) * quantum;
  std::vector<std::int64_t> fixed(metres.size());
  for (std::size_t k = 0; k < metres.size(); ++k) {
    if (!std::isfinite(metres[k]))
      throw input_error(what + ": vertex " + std::to_string(k) + " is not a finite height");
    if (std::fabs(metres[k]) > limit)
      throw input_error(what + ": vertex " + std::to_string(k) + " lies beyond the terrain's " +
                        "range of 2^53 height quanta");
    fixed[k] = std::llround(metres[k] / quantum);
  }
  return fixed;
}

}  // namespace

void ImposedChange::impose(DeviceTerrain& terrain, const std::vector<double>& metres,
                           bool layered) {
  if (layered) throw input_error("set_elevation: not with a layer stack (ground.layers)");
  const std::vector<std::int64_t> before = terrain.download_fixed();
  const std::vector<std::int64_t> after =
      heights_in_quanta(metres, terrain.quantum(), before.size(), "set_elevation");
  terrain.upload_fixed(after);
  add(before, after);
}

void ImposedChange::add(const std::vector<std::int64_t>& before,
                        const std::vector<std::int64_t>& after) {
  if (per_vertex_.empty()) per_vertex_.assign(after.size(), 0);
  for (std::size_t k = 0; k < after.size(); ++k) {
    const std::int64_t d = after[k] - before[k];
    per_vertex_[k] += d;
    total_ += d;
  }
}

void ImposedChange::raise(Heightmap& reference, double quantum) const {
  for (std::size_t k = 0; k < per_vertex_.size(); ++k)
    reference.h[k] += static_cast<float>(static_cast<double>(per_vertex_[k]) * quantum);
}

void ImposedChange::store(std::vector<StoredField>& fields) const {
  if (per_vertex_.empty()) return;
  fields.push_back({kImposedElevationChange, 1, {}, per_vertex_});
}

void ImposedChange::restore(const std::vector<StoredField>& fields) {
  per_vertex_.clear();
  total_ = 0;
  for (const StoredField& f : fields) {
    if (f.name != kImposedElevationChange) continue;
    per_vertex_ = f.i64;
    for (std::int64_t d : per_vertex_) total_ += d;
  }
}

std::vector<double> heights_in_metres(DeviceTerrain& terrain) {
  const std::vector<std::int64_t> fixed = terrain.download_fixed();
  std::vector<double> metres(fixed.size());
  for (std::size_t k = 0; k < fixed.size(); ++k)
    metres[k] = static_cast<double>(fixed[k]) * terrain.quantum();
  return metres;
}

}  // namespace runnel
