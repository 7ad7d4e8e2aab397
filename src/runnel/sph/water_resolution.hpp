// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "runnel/core/heightmap.hpp"

namespace runnel {

// How well the particles on the bed resolve the water there (docs/erosion.md, "Films"). A particle
// is on the bed as erode_exchange decides: touching the ground, or within the water depth D it
// reads, along the surface normal. Its footprint holds some particles' water
// (water_depth_reference.hpp); with fewer than kFilmNeighbours besides its own it is a film, whose
// depth is read over a coarser footprint, and an unresolved film where even the coarsest holds
// less: a drop on its own, as deep as its own footprint says, so that erosion there depends on the
// particle size.
// The share of unresolved films above which `runnel run` cautions.
inline constexpr double kUnresolvedShareWarning = 0.2;

struct WaterResolution {
  long long bed_particles = 0;
  double film_share = 0;        // of the bed particles, films (resolved on a coarser level or not)
  double unresolved_share = 0;  // of the bed particles, films that no level resolved
  double median_particles_per_footprint = 0;  // on the fine footprint, own water included; 0
                                              // without bed particles
};

struct ParticlesOnTerrain {
  const std::vector<float>& x;
  const std::vector<float>& y;
  const std::vector<float>& z;
  const std::vector<float>& depth;             // m, each particle's D (water_depth.cl)
  const std::vector<std::uint32_t>& contacts;  // kTouchingFlag: on the ground (particle_store.hpp)
};

WaterResolution water_resolution(const ParticlesOnTerrain& p, const Heightmap& terrain,
                                 double particle_volume, double footprint_radius,
                                 double contact_radius);

}  // namespace runnel
