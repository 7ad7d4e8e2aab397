// SPDX-License-Identifier: MIT
#pragma once
#include "runnel/models/interaction.hpp"
#include "runnel/sph/particle_store.hpp"

namespace runnel {

// The water SPH particles stand for, per vertex of an nx × ny grid of spacing `cell`: each
// particle's volume (spacing³) spread bilinearly over the four vertices around it, then smoothed
// by one 1-2-1 pass in x and in z that scatters (so the total volume is kept to rounding), as a
// depth = volume / cell². A particle is a few cells apart from its neighbours in a thin sheet, and
// the pass turns their dots into one surface. Load: sediment volume over water volume; speed: the
// volume-weighted mean. `points` holds x, y, z and load of every particle.
WaterView bin_particles(const HostParticles& particles, int nx, int ny, double cell, double spacing,
                        double volume_quantum);

}  // namespace runnel
