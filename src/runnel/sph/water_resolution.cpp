// SPDX-License-Identifier: MIT
#include "runnel/sph/water_resolution.hpp"

#include <algorithm>

#include "runnel/core/vertex_normals.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/water_depth_reference.hpp"
#include "runnel/terrain/surface.hpp"

namespace runnel {

WaterResolution water_resolution(const ParticlesOnTerrain& p, const Heightmap& terrain,
                                 double particle_volume, double footprint_radius,
                                 double contact_radius) {
  const std::vector<float> normals = terrain_normals_reference(terrain);
  const std::vector<DepthReading> readings = water_depth_reference(
      p.x, p.z, terrain.nx, terrain.ny, terrain.cell, footprint_radius, particle_volume);
  std::vector<double> per_footprint;
  long long films = 0, unresolved = 0;
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    const SurfacePointReference s = surface_point(terrain, normals, p.x[i], p.z[i]);
    const double depth = std::max(static_cast<double>(p.depth[i]), 1e-6);
    const bool touching = p.contacts[i] & kTouchingFlag;
    if (!touching && (p.y[i] - s.height) * s.normal[1] - contact_radius > depth)
      continue;  // in the air
    per_footprint.push_back(readings[i].fine_particles);
    films += readings[i].level > 0 || !readings[i].resolved;
    unresolved += !readings[i].resolved;
  }
  WaterResolution r;
  r.bed_particles = static_cast<long long>(per_footprint.size());
  if (per_footprint.empty()) return r;
  r.film_share = static_cast<double>(films) / static_cast<double>(r.bed_particles);
  r.unresolved_share = static_cast<double>(unresolved) / static_cast<double>(r.bed_particles);
  const auto middle = per_footprint.begin() + static_cast<std::ptrdiff_t>(per_footprint.size() / 2);
  std::nth_element(per_footprint.begin(), middle, per_footprint.end());
  r.median_particles_per_footprint = *middle;
  return r;
}

}  // namespace runnel
