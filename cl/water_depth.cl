// SPDX-License-Identifier: MIT
// The depth of the water on the bed, at the terrain's own resolution (physics.md §4; docs/erosion.md):
// every particle's volume V is counted on the vertices of its footprint (footprint.cl), vertex k
// then holds the water over its cell, depth_k = Σ_i V_i ŵ_ik / cell², and each particle reads the
// footprint-weighted mean of that field at its position, D_i = Σ_k ŵ_ik depth_k. D is the depth of
// the bed friction (integrate.cl) and the erosion law (erode.cl). Measured at the scale of the
// terrain's cells rather than of the particles, it does not change with the particle size: eight
// particles of half the spacing put the same water on a cell as one of the full spacing.
// The counts are integers (WATER_QUANTUM m of depth per count) added with integer atomics, so the
// field does not depend on the order of the work-items.
// Compile-time constants (host -D): FOOTPRINT_RADIUS, WATER_PARTICLE_VOLUME (m³).

#define WATER_QUANTUM 1e-6f  // m

__kernel void water_depth_scatter(const __global float* x, const __global float* z, const __global uint* id,
                                  const uint n, volatile __global long* water, const int tnx, const int tny,
                                  const float tcell) {
  const uint i = get_global_id(0);
  if (i >= n || (id[i] & DEAD_FLAG)) return;
  const long counts = (long)round(WATER_PARTICLE_VOLUME / (WATER_QUANTUM * tcell * tcell));
  spread_quanta(water, tnx, tny, tcell, x[i], z[i], counts, 1, 0.5f, 0, 1.0f);
}

__kernel void water_depth_gather(const __global float* x, const __global float* z, const __global uint* id,
                                 const uint n, const __global long* water, const int tnx, const int tny,
                                 const float tcell, __global float* depth) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  depth[i] = (id[i] & DEAD_FLAG) ? 0.0f : footprint_mean(water, WATER_QUANTUM, tnx, tny, tcell, x[i], z[i]);
}
