// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "runnel/core/heightmap.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/sph_settings.hpp"

namespace runnel {

// Standing water as SPH particles (docs/physics.md, "Standing water"): a lattice at the particle
// spacing, columns (i + ½, k + ½)·dx over the terrain, each filled from the contact surface (or
// higher, the contact radius clear of every triangle) up to the water's top (bed + the depth field
// interpolated on the terrain's triangles, at most the wet vertices' surface); at rest, at the
// hydrostatic density of the weakly compressible fluid (ρ0 for the incompressible solver), never
// evaporating. `depth` is per vertex of `terrain` (initial_water_depth).
HostParticles standing_water_particles(const SphSettings& s, const Heightmap& terrain,
                                       const std::vector<float>& depth);

}  // namespace runnel
