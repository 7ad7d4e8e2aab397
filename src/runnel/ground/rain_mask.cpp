// SPDX-License-Identifier: MIT
#include "runnel/ground/rain_mask.hpp"

#include "runnel/ground/ground.hpp"
#include "runnel/ground/ground_settings.hpp"

namespace runnel {

RainMask::RainMask(const Parameters& params, int nx, int ny) {
  if (has_rain_mask(params)) scenario_ = rain_weights(params, nx, ny);
  weights_ = scenario_;
}

void RainMask::paint(const std::vector<int>& vertices, float value) {
  if (!present()) return;
  for (int k : vertices) weights_[static_cast<std::size_t>(k)] = value;
  painted_ = true;
}

void RainMask::set(std::vector<float> weights) {
  weights_ = std::move(weights);
  painted_ = true;
}

void RainMask::store(std::vector<StoredField>& fields) const {
  if (painted_) fields.push_back({kGroundRainMask, 1, weights_, {}});
}

void RainMask::restore(const std::vector<StoredField>& fields) {
  weights_ = scenario_;
  painted_ = false;
  for (const StoredField& f : fields) {
    // A run without a scenario mask takes the one a coupler set (the reader checked its size).
    if (f.name == kGroundRainMask && (scenario_.empty() || f.f32.size() == weights_.size())) {
      weights_ = f.f32;
      painted_ = true;
    }
  }
}

}  // namespace runnel
