// SPDX-License-Identifier: MIT
#include "runnel/models/water_surface.hpp"

#include <algorithm>
#include <cmath>

#include "runnel/terrain/surface.hpp"

namespace runnel {

WaterSurface grid_water_surface(const Heightmap& t, const WaterView& view) {
  WaterSurface s{t.nx, t.ny, t.cell, t.h, view.depth, view.load, view.velocity};
  s.depth.resize(t.size(), 0.0f);
  s.load.resize(t.size(), 0.0f);
  s.velocity.resize(2 * t.size(), 0.0f);
  return s;
}

WaterSurface particle_water_surface(const Heightmap& t, const WaterView& view, double spacing) {
  const int refine = std::max(1, static_cast<int>(std::lround(t.cell / spacing)));
  WaterSurface s;
  s.nx = (t.nx - 1) * refine + 1;
  s.ny = (t.ny - 1) * refine + 1;
  s.cell = t.cell / refine;
  const std::size_t n = static_cast<std::size_t>(s.nx) * s.ny;
  s.ground.resize(n);
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i)
      s.ground[static_cast<std::size_t>(j) * s.nx + i] =
          static_cast<float>(surface_height(t, i * s.cell, j * s.cell));

  struct Sums {
    double volume = 0, sediment = 0, flow_x = 0, flow_z = 0;
  };
  std::vector<Sums> sums(n);
  const double radius = 2.0 * spacing, particle = spacing * spacing * spacing;
  const int reach = static_cast<int>(std::ceil(radius / s.cell));
  const std::size_t count = view.points.size() / 4;
  std::vector<double> weight;
  for (std::size_t p = 0; p < count; ++p) {
    const double x = view.points[4 * p], z = view.points[4 * p + 2];
    const int ci = std::clamp(static_cast<int>(std::lround(x / s.cell)), 0, s.nx - 1),
              cj = std::clamp(static_cast<int>(std::lround(z / s.cell)), 0, s.ny - 1);
    const int i0 = std::max(0, ci - reach), i1 = std::min(s.nx - 1, ci + reach),
              j0 = std::max(0, cj - reach), j1 = std::min(s.ny - 1, cj + reach);
    // The kernel over the vertices it reaches, normalised there: a particle's whole volume lands
    // on the grid, also at the terrain's edge and off it.
    weight.clear();
    double total = 0;
    const double inverse_r2 = 1.0 / (radius * radius);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double dx = i * s.cell - x, dz = j * s.cell - z;
        const double q2 = (dx * dx + dz * dz) * inverse_r2;
        const double w = q2 < 1.0 ? (1.0 - q2) * (1.0 - q2) * (1.0 - q2) : 0.0;
        weight.push_back(w);
        total += w;
      }
    if (total <= 0) {  // off the grid by more than the kernel: the nearest vertex takes it all
      weight.assign(weight.size(), 0.0);
      weight[static_cast<std::size_t>(cj - j0) * (i1 - i0 + 1) + (ci - i0)] = total = 1.0;
    }
    const double load = view.points[4 * p + 3];
    const double vx = 2 * p < view.point_velocity.size() ? view.point_velocity[2 * p] : 0.0,
                 vz = 2 * p + 1 < view.point_velocity.size() ? view.point_velocity[2 * p + 1] : 0.0;
    const double share = particle / total;
    std::size_t w = 0;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i, ++w) {
        if (weight[w] == 0.0) continue;
        Sums& sum = sums[static_cast<std::size_t>(j) * s.nx + i];
        const double v = share * weight[w];
        sum.volume += v;
        sum.sediment += v * load;
        sum.flow_x += v * vx;
        sum.flow_z += v * vz;
      }
  }
  s.depth.resize(n);
  s.load.assign(n, 0.0f);
  s.velocity.assign(2 * n, 0.0f);
  const double area = s.cell * s.cell;
  for (std::size_t k = 0; k < n; ++k) {
    const Sums& sum = sums[k];
    s.depth[k] = static_cast<float>(sum.volume / area);
    if (sum.volume <= 0) continue;
    s.load[k] = static_cast<float>(sum.sediment / sum.volume);
    s.velocity[2 * k] = static_cast<float>(sum.flow_x / sum.volume);
    s.velocity[2 * k + 1] = static_cast<float>(sum.flow_z / sum.volume);
  }
  return s;
}

}  // namespace runnel
