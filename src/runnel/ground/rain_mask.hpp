// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "runnel/core/parameters.hpp"
#include "runnel/core/stored_field.hpp"

namespace runnel {

inline constexpr const char* kGroundRainMask = "ground__rain_mask";

// A run's rain mask (ground.rain_mask: the fraction of the scenario's rain falling at each vertex)
// as it stands now: the scenario's, or as painted in runnel-viewer. A painted mask goes into the
// checkpoint (ground__rain_mask); a checkpoint without one restores the scenario's.
class RainMask {
 public:
  RainMask() = default;
  // The scenario's mask (empty without ground.rain_mask), read from its file or given.
  RainMask(const Parameters& params, int nx, int ny);
  explicit RainMask(std::vector<float> scenario)
      : scenario_(scenario), weights_(std::move(scenario)) {}
  bool present() const { return !weights_.empty(); }
  const std::vector<float>& weights() const { return weights_; }
  void paint(const std::vector<int>& vertices, float value);
  // Every vertex's weight at once (a coupler's rain field): a run without a scenario mask gets one.
  void set(std::vector<float> weights);
  // Appends the painted mask to a checkpoint's fields; restore() takes it back (or the scenario's).
  void store(std::vector<StoredField>& fields) const;
  void restore(const std::vector<StoredField>& fields);

 private:
  std::vector<float> scenario_, weights_;
  bool painted_ = false;
};

}  // namespace runnel
