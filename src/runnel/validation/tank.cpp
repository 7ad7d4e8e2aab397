// SPDX-License-Identifier: MIT
#include "runnel/validation/tank.hpp"

#include <cmath>

namespace runnel {

Heightmap flat_floor(int x_cells, int z_cells, double cell) {
  return Heightmap(x_cells + 1, z_cells + 1, cell, 0.0f);
}

HostParticles uniform_block(const SphSettings& s, double lx, double ly, double lz) {
  HostParticles p = hydrostatic_block(s, lx, ly, lz);
  for (float& rho : p.f[kRho]) rho = static_cast<float>(s.rho0);
  return p;
}

HostParticles hydrostatic_block(const SphSettings& s, double lx, double ly, double lz) {
  const double dx = s.spacing;
  const int nx = static_cast<int>(std::lround(lx / dx));
  const int ny = static_cast<int>(std::lround(ly / dx));
  const int nz = static_cast<int>(std::lround(lz / dx));
  HostParticles p;
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const double y = (j + 0.5) * dx;
        const double pressure = s.rho0 * s.gravity * (ly - y);
        const double rho = s.rho0 * std::pow(1.0 + pressure / s.tait_b(), 1.0 / 7.0);
        p.push(static_cast<float>((i + 0.5) * dx), static_cast<float>(y),
               static_cast<float>((k + 0.5) * dx), 0, 0, 0, static_cast<float>(rho), 1e30f);
      }
    }
  }
  return p;
}

}  // namespace runnel
