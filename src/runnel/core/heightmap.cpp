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

Heightmap height_change(const Heightmap& before, const Heightmap& after) {
  Heightmap change = before;
  for (std::size_t k = 0; k < change.size(); ++k) change.h[k] = after.h[k] - before.h[k];
  return change;
}

Heightmap subsample(const Heightmap& t, int factor) {
  if (factor <= 1) return t;
  Heightmap out((t.nx - 1) / factor + 1, (t.ny - 1) / factor + 1, t.cell * factor);
  out.origin_x = t.origin_x;
  out.origin_z = t.origin_z;
  out.georef = t.georef;
  for (int j = 0; j < out.ny; ++j)
    for (int i = 0; i < out.nx; ++i) out.at(i, j) = t.at(i * factor, j * factor);
  return out;
}

}  // namespace runnel
