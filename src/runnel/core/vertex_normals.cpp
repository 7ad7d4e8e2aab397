// SPDX-License-Identifier: MIT
#include "runnel/core/vertex_normals.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {

std::vector<float> terrain_normals_reference(const Heightmap& t) {
  std::vector<float> n(t.size() * 3);
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) {
      const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, t.nx - 1);
      const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, t.ny - 1);
      const double dhdx = (double(t.at(i1, j)) - t.at(i0, j)) / ((i1 - i0) * t.cell);
      const double dhdz = (double(t.at(i, j1)) - t.at(i, j0)) / ((j1 - j0) * t.cell);
      const double len = std::sqrt(dhdx * dhdx + 1.0 + dhdz * dhdz);
      const std::size_t k = static_cast<std::size_t>(j) * t.nx + i;
      n[3 * k + 0] = static_cast<float>(-dhdx / len);
      n[3 * k + 1] = static_cast<float>(1.0 / len);
      n[3 * k + 2] = static_cast<float>(-dhdz / len);
    }
  }
  return n;
}

}  // namespace runnel
