// SPDX-License-Identifier: MIT
#include "runnel/models/water_binning.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {
namespace {

// One scattering 1-2-1 pass along x (stride 1) or z (stride nx): a vertex keeps half its value
// and gives a quarter to each neighbour; at an edge the missing neighbour's quarter stays home.
void smooth(std::vector<double>& v, int nx, int ny, bool along_x) {
  std::vector<double> out(v.size(), 0.0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      const int pos = along_x ? i : j, end = along_x ? nx : ny;
      const std::size_t stride = along_x ? 1 : static_cast<std::size_t>(nx);
      const double quarter = 0.25 * v[k];
      out[k] += 0.5 * v[k];
      if (pos > 0)
        out[k - stride] += quarter;
      else
        out[k] += quarter;
      if (pos + 1 < end)
        out[k + stride] += quarter;
      else
        out[k] += quarter;
    }
  }
  v.swap(out);
}

}  // namespace

WaterView bin_particles(const HostParticles& p, int nx, int ny, double cell, double spacing,
                        double volume_quantum) {
  const std::size_t n = static_cast<std::size_t>(nx) * ny;
  std::vector<double> volume(n, 0.0), sediment(n, 0.0), speed(n, 0.0), flow_x(n, 0.0),
      flow_z(n, 0.0);
  WaterView view;
  view.spacing = spacing;
  view.points.reserve(4 * p.size());
  view.point_velocity.reserve(2 * p.size());
  const double particle = spacing * spacing * spacing;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double x = std::clamp(p.f[kX][i] / cell, 0.0, nx - 1.0),
                 z = std::clamp(p.f[kZ][i] / cell, 0.0, ny - 1.0);
    const int i0 = std::min(static_cast<int>(x), nx - 2),
              j0 = std::min(static_cast<int>(z), ny - 2);
    const double fx = x - i0, fz = z - j0;
    const double load = p.sediment[i] * volume_quantum;
    const double v = std::sqrt(p.f[kVx][i] * p.f[kVx][i] + p.f[kVy][i] * p.f[kVy][i] +
                               p.f[kVz][i] * p.f[kVz][i]);
    const double w[4] = {(1 - fx) * (1 - fz), fx * (1 - fz), (1 - fx) * fz, fx * fz};
    const std::size_t k[4] = {
        static_cast<std::size_t>(j0) * nx + i0, static_cast<std::size_t>(j0) * nx + i0 + 1,
        static_cast<std::size_t>(j0 + 1) * nx + i0, static_cast<std::size_t>(j0 + 1) * nx + i0 + 1};
    for (int c = 0; c < 4; ++c) {
      volume[k[c]] += w[c] * particle;
      sediment[k[c]] += w[c] * load;
      speed[k[c]] += w[c] * particle * v;
      flow_x[k[c]] += w[c] * particle * p.f[kVx][i];
      flow_z[k[c]] += w[c] * particle * p.f[kVz][i];
    }
    view.points.insert(view.points.end(),
                       {p.f[kX][i], p.f[kY][i], p.f[kZ][i], static_cast<float>(load / particle)});
    view.point_velocity.insert(view.point_velocity.end(), {p.f[kVx][i], p.f[kVz][i]});
  }
  for (auto* field : {&volume, &sediment, &speed, &flow_x, &flow_z}) {
    smooth(*field, nx, ny, true);
    smooth(*field, nx, ny, false);
  }
  view.depth.resize(n);
  view.load.resize(n);
  view.speed.resize(n);
  view.velocity.resize(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    if (volume[k] > 0) {
      view.velocity[2 * k] = static_cast<float>(flow_x[k] / volume[k]);
      view.velocity[2 * k + 1] = static_cast<float>(flow_z[k] / volume[k]);
    }
    view.depth[k] = static_cast<float>(volume[k] / (cell * cell));
    view.load[k] = volume[k] > 0 ? static_cast<float>(sediment[k] / volume[k]) : 0.0f;
    view.speed[k] = volume[k] > 0 ? static_cast<float>(speed[k] / volume[k]) : 0.0f;
  }
  return view;
}

}  // namespace runnel
