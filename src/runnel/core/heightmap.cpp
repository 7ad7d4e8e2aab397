// SPDX-License-Identifier: MIT
#include "runnel/core/heightmap.hpp"

#include <algorithm>

namespace runnel {

float Heightmap::min_height() const {
  return h.empty() ? 0.0f : *std::min_element(h.begin(), h.end());
}
float Heightmap::max_height() const {
  return h.empty() ? 0.0f : *std::max_element(h.begin(), h.end());
}

double Heightmap::volume() const {
  // Pairwise-free plain sum in double: 1e8 floats keep ~1e-8 relative accuracy, enough for reports.
  double sum = 0.0;
  for (float v : h) sum += v;
  return sum * cell * cell;
}

}  // namespace runnel
