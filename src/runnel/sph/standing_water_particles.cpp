// SPDX-License-Identifier: MIT
#include "runnel/sph/standing_water_particles.hpp"

#include <cmath>

#include "runnel/terrain/surface.hpp"

namespace runnel {

HostParticles standing_water_particles(const SphSettings& s, const Heightmap& terrain,
                                       const std::vector<float>& depth) {
  HostParticles p;
  Heightmap water(terrain.nx, terrain.ny, terrain.cell);
  water.h = depth;
  const double dx = s.spacing;
  // The columns stand on the contact surface (the terrain raised by the contact radius along its
  // normal, as the drift keeps particles): beside a steep wall the bed's own height would put the
  // lowest particles inside the wall's reach, compressed far beyond ρ0 at the first step.
  const Heightmap floor = contact_surface(terrain, s.contact_radius);
  const int columns_x = static_cast<int>(std::floor((terrain.nx - 1) * terrain.cell / dx));
  const int columns_z = static_cast<int>(std::floor((terrain.ny - 1) * terrain.cell / dx));
  for (int k = 0; k < columns_z; ++k)
    for (int i = 0; i < columns_x; ++i) {
      const double x = (i + 0.5) * dx, z = (k + 0.5) * dx;
      const double column = surface_height(water, x, z);
      if (column < 0.5 * dx) continue;  // not a particle's worth of water
      const double bed = surface_height(terrain, x, z), top = bed + column;
      const double lowest = surface_height(floor, x, z);
      for (int layer = 0; lowest + layer * dx < top; ++layer) {
        const double y = lowest + layer * dx;
        const double pressure = s.rho0 * s.gravity * (top - y);
        const double rho =
            s.incompressible() ? s.rho0 : s.rho0 * std::pow(1.0 + pressure / s.tait_b(), 1.0 / 7.0);
        p.push(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z), 0, 0, 0,
               static_cast<float>(rho), 1e30f);
      }
    }
  return p;
}

}  // namespace runnel
