// SPDX-License-Identifier: MIT
#include "runnel/models/interaction.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {

std::vector<int> vertices_in_disc(int nx, int ny, double cell, const RainDisc& disc) {
  std::vector<int> inside;
  if (disc.radius <= 0 || cell <= 0) return inside;
  const int i0 = std::max(0, static_cast<int>(std::floor((disc.x - disc.radius) / cell)));
  const int i1 = std::min(nx - 1, static_cast<int>(std::ceil((disc.x + disc.radius) / cell)));
  const int j0 = std::max(0, static_cast<int>(std::floor((disc.z - disc.radius) / cell)));
  const int j1 = std::min(ny - 1, static_cast<int>(std::ceil((disc.z + disc.radius) / cell)));
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const double dx = i * cell - disc.x, dz = j * cell - disc.z;
      if (dx * dx + dz * dz <= disc.radius * disc.radius) inside.push_back(j * nx + i);
    }
  }
  return inside;
}

}  // namespace runnel
