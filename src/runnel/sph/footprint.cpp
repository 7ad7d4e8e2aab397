// SPDX-License-Identifier: MIT
#include "runnel/sph/footprint.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {

double footprint_axis_weight(double d, double radius) {
  const double t = std::max(0.0, 1.0 - d * d / (radius * radius));
  return t * t;
}

std::vector<FootprintWeight> footprint_weights(double x, double z, int nx, int ny, double cell,
                                               double radius) {
  const int i0 = std::max(0, static_cast<int>(std::ceil((x - radius) / cell)));
  const int i1 = std::min(nx - 1, static_cast<int>(std::floor((x + radius) / cell)));
  const int j0 = std::max(0, static_cast<int>(std::ceil((z - radius) / cell)));
  const int j1 = std::min(ny - 1, static_cast<int>(std::floor((z + radius) / cell)));
  std::vector<FootprintWeight> out;
  double total = 0;
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const double w =
          footprint_axis_weight(i * cell - x, radius) * footprint_axis_weight(j * cell - z, radius);
      out.push_back({i, j, w});
      total += w;
    }
  }
  for (auto& f : out) f.weight /= total;
  return out;
}

double lone_particle_depth(double volume, double x, double z, int nx, int ny, double cell,
                           double radius) {
  double sum = 0;
  for (const auto& f : footprint_weights(x, z, nx, ny, cell, radius)) sum += f.weight * f.weight;
  return volume * sum / (cell * cell);
}

}  // namespace runnel
