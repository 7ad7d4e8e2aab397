// SPDX-License-Identifier: MIT
#include "runnel/sph/water_resolution.hpp"

#include <algorithm>

#include "runnel/core/vertex_normals.hpp"
#include "runnel/sph/footprint.hpp"
#include "runnel/terrain/surface.hpp"

namespace runnel {

WaterResolution water_resolution(const ParticlesOnTerrain& p, const Heightmap& terrain,
                                 double particle_volume, double footprint_radius,
                                 double contact_radius) {
  const std::vector<float> normals = terrain_normals_reference(terrain);
  std::vector<double> per_footprint;
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    const SurfacePointReference s = surface_point(terrain, normals, p.x[i], p.z[i]);
    const double depth = std::max(static_cast<double>(p.depth[i]), 1e-6);
    if ((p.y[i] - s.height) * s.normal[1] - contact_radius > depth) continue;  // in the air
    const double own = lone_particle_depth(particle_volume, p.x[i], p.z[i], terrain.nx, terrain.ny,
                                           terrain.cell, footprint_radius);
    if (own > 0) per_footprint.push_back(depth / own);
  }
  WaterResolution r;
  r.bed_particles = static_cast<long long>(per_footprint.size());
  if (per_footprint.empty()) return r;
  const auto films = std::count_if(per_footprint.begin(), per_footprint.end(),
                                   [](double n) { return n < kFilmParticles; });
  r.film_share = static_cast<double>(films) / static_cast<double>(per_footprint.size());
  const auto middle = per_footprint.begin() + static_cast<std::ptrdiff_t>(per_footprint.size() / 2);
  std::nth_element(per_footprint.begin(), middle, per_footprint.end());
  r.median_particles_per_footprint = *middle;
  return r;
}

}  // namespace runnel
