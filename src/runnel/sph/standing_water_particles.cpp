// SPDX-License-Identifier: MIT
#include "runnel/sph/standing_water_particles.hpp"

#include <algorithm>
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
  // lowest particles inside the wall's reach, compressed far beyond ρ0 at the first step. On a
  // face steeper than the contact surface follows (its raise is capped at 5 radii) a column starts
  // higher still, where it is the contact radius from every triangle, and no column rises above
  // the wet vertices' surface: bed + interpolated depth climbs a bank above a lake's level.
  const Heightmap floor = contact_surface(terrain, s.contact_radius);
  const double clearance = s.contact_radius * (1 - 1e-4);  // a flat floor's lowest layer passes
  const auto clear_of_terrain = [&](double x, double y, double z) {
    return distance_to_surface(terrain, x, y, z, s.contact_radius) >= clearance;
  };
  const int columns_x = static_cast<int>(std::floor((terrain.nx - 1) * terrain.cell / dx));
  const int columns_z = static_cast<int>(std::floor((terrain.ny - 1) * terrain.cell / dx));
  for (int k = 0; k < columns_z; ++k)
    for (int i = 0; i < columns_x; ++i) {
      const double x = (i + 0.5) * dx, z = (k + 0.5) * dx;
      const double column = surface_height(water, x, z);
      if (column < 0.5 * dx) continue;  // not a particle's worth of water
      const double bed = surface_height(terrain, x, z);
      const double top = std::min(bed + column, wet_surface_height(terrain, depth, x, z));
      double lowest = surface_height(floor, x, z);
      if (lowest >= top) continue;
      if (!clear_of_terrain(x, lowest, z)) {
        // The distance to a heightmap grows with height: bisect for the lowest clear point.
        if (!clear_of_terrain(x, top, z)) continue;
        double below = lowest, above = top;
        for (int n = 0; n < 40; ++n) {
          const double mid = 0.5 * (below + above);
          (clear_of_terrain(x, mid, z) ? above : below) = mid;
        }
        lowest = above;
      }
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
