// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/core/heightmap.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/sph_settings.hpp"

namespace runnel {

// A flat floor at height 0 spanning [0, nx_cells·cell] × [0, nz_cells·cell]: the tank's bottom.
Heightmap flat_floor(int x_cells, int z_cells, double cell);

// A block of particles on a lattice of spacing dx filling [0, lx] × [0, ly] × [0, lz] (cell
// centres), at rest, with the hydrostatic density of a column whose free surface is at ly:
// ρ = ρ0 (1 + ρ0 g (ly − y) / B)^(1/7).
HostParticles hydrostatic_block(const SphSettings& s, double lx, double ly, double lz);
// The same lattice at rest with uniform density ρ0 (a start that is not the hydrostatic answer).
HostParticles uniform_block(const SphSettings& s, double lx, double ly, double lz);

}  // namespace runnel
