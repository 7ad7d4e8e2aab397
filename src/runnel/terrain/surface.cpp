// SPDX-License-Identifier: MIT
#include "runnel/terrain/surface.hpp"

#include <algorithm>
#include <cmath>

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

SurfacePointReference surface_point(const Heightmap& t, const std::vector<float>& normals, double x,
                                    double z) {
  const double u = std::clamp(x / t.cell, 0.0, t.nx - 1.0),
               v = std::clamp(z / t.cell, 0.0, t.ny - 1.0);
  const int i = std::min(static_cast<int>(u), t.nx - 2),
            j = std::min(static_cast<int>(v), t.ny - 2);
  const double fx = u - i, fz = v - j;
  const std::size_t k00 = static_cast<std::size_t>(j) * t.nx + i, k10 = k00 + 1, k01 = k00 + t.nx,
                    k11 = k01 + 1;
  double w00, w10, w01, w11;
  if (fx >= fz) {
    w00 = 1 - fx, w10 = fx - fz, w11 = fz, w01 = 0;
  } else {
    w00 = 1 - fz, w01 = fz - fx, w11 = fx, w10 = 0;
  }
  SurfacePointReference s;
  s.height = w00 * t.h[k00] + w10 * t.h[k10] + w01 * t.h[k01] + w11 * t.h[k11];
  double length = 0;
  for (int a = 0; a < 3; ++a) {
    s.normal[a] = w00 * normals[3 * k00 + a] + w10 * normals[3 * k10 + a] +
                  w01 * normals[3 * k01 + a] + w11 * normals[3 * k11 + a];
    length += s.normal[a] * s.normal[a];
  }
  for (double& c : s.normal) c /= std::sqrt(length);
  return s;
}

Heightmap contact_surface(const Heightmap& t, double radius) {
  Heightmap c = t;
  const std::vector<float> n = terrain_normals_reference(t);
  for (std::size_t k = 0; k < c.size(); ++k)
    c.h[k] += static_cast<float>(radius / std::max(0.2, static_cast<double>(n[3 * k + 1])));
  return c;
}

}  // namespace runnel
