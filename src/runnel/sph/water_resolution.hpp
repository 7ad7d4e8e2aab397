// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/core/heightmap.hpp"

namespace runnel {

// How well particles resolve the water on the bed (docs/erosion.md, "Unresolved films"). For each
// particle on the bed (within the water depth D it reads, along the surface normal, as
// erode_exchange decides) the water its footprint holds, in particles: D against the depth its own
// water alone gives, lone_particle_depth (footprint.hpp). Under two, the particle is a film of its
// own: it claims the bed area of its footprint whatever its volume, so erosion there depends on the
// particle size, and the more so the larger the share of such films (measured in the README).
inline constexpr double kFilmParticles = 2.0;
// The film share above which `runnel run` cautions: in the convergence case's storms, at 26 % of
// films the eroded volume moved by 9 % when the particle spacing halved, at 8 % by 4 % (README,
// "Rain erosion").
inline constexpr double kFilmShareWarning = 0.2;

struct WaterResolution {
  long long bed_particles = 0;
  double film_share = 0;                      // of the bed particles, those under kFilmParticles
  double median_particles_per_footprint = 0;  // 0 without bed particles
};

struct ParticlesOnTerrain {
  const std::vector<float>& x;
  const std::vector<float>& y;
  const std::vector<float>& z;
  const std::vector<float>& depth;  // m, each particle's D (water_depth.cl)
};

WaterResolution water_resolution(const ParticlesOnTerrain& p, const Heightmap& terrain,
                                 double particle_volume, double footprint_radius,
                                 double contact_radius);

}  // namespace runnel
