// SPDX-License-Identifier: MIT
#include "runnel/terrain/surface.hpp"

#include <algorithm>

#include "runnel/terrain/terrain_normals.hpp"

namespace runnel {

double surface_height(const Heightmap& t, double x, double z) {
  const double u = std::clamp(x / t.cell, 0.0, t.nx - 1.0),
               v = std::clamp(z / t.cell, 0.0, t.ny - 1.0);
  const int i = std::min(static_cast<int>(u), t.nx - 2),
            j = std::min(static_cast<int>(v), t.ny - 2);
  const double fx = u - i, fz = v - j;
  const double h00 = t.at(i, j), h10 = t.at(i + 1, j), h01 = t.at(i, j + 1),
               h11 = t.at(i + 1, j + 1);
  if (fx >= fz) return h00 * (1 - fx) + h10 * (fx - fz) + h11 * fz;
  return h00 * (1 - fz) + h01 * (fz - fx) + h11 * fx;
}

Heightmap contact_surface(const Heightmap& t, double radius) {
  Heightmap c = t;
  const std::vector<float> n = terrain_normals_reference(t);
  for (std::size_t k = 0; k < c.size(); ++k)
    c.h[k] += static_cast<float>(radius / std::max(0.2, static_cast<double>(n[3 * k + 1])));
  return c;
}

}  // namespace runnel
