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
// Compile-time constants (host -D): FOOTPRINT_RADIUS, FOOTPRINT_SIDE, WATER_PARTICLE_VOLUME (m³),
// WATER_RUN.

#define WATER_QUANTUM 1e-6f  // m

// A particle's volume in counts on a cell.
inline long water_counts(float tcell) {
  return (long)round(WATER_PARTICLE_VOLUME / (WATER_QUANTUM * tcell * tcell));
}

// The counts of a run of particles gathered in private memory before they go out with atomics: the
// particles of a run are consecutive in the cell order, so where the water is deep their footprints
// overlap, and the atomics on the vertices they share were most of the pass and made the cores wait
// on each other. A box of WATER_BOX × WATER_BOX vertices anchored at (i0, j0), holding
// [lo_i, hi_i] × [lo_j, hi_j] (relative to the anchor) so far.
#define WATER_BOX (FOOTPRINT_SIDE + 4)
typedef struct {
  long count[WATER_BOX * WATER_BOX];
  int i0, j0, lo_i, hi_i, lo_j, hi_j;
} WaterBox;

// Nothing held (the counts are all 0).
inline void water_box_clear_range(WaterBox* b) {
  b->lo_i = b->lo_j = WATER_BOX;
  b->hi_i = b->hi_j = -1;
}

// An empty box moved to f, centred on it so that the neighbours' footprints fit too.
inline void water_box_anchor(WaterBox* b, const Footprint* f) {
  b->i0 = f->i0 - 2;
  b->j0 = f->j0 - 2;
}

// f's vertices are now held too.
inline void water_box_cover(WaterBox* b, const Footprint* f) {
  b->lo_i = min(b->lo_i, f->i0 - b->i0);
  b->hi_i = max(b->hi_i, f->i1 - b->i0);
  b->lo_j = min(b->lo_j, f->j0 - b->j0);
  b->hi_j = max(b->hi_j, f->j1 - b->j0);
}

inline bool water_box_holds(const WaterBox* b, const Footprint* f) {
  return f->i0 >= b->i0 && f->j0 >= b->j0 && f->i1 < b->i0 + WATER_BOX && f->j1 < b->j0 + WATER_BOX;
}

inline void water_box_flush(WaterBox* b, volatile __global long* water, int nx) {
  for (int j = b->lo_j; j <= b->hi_j; ++j) {
    for (int i = b->lo_i; i <= b->hi_i; ++i) {
      const long c = b->count[j * WATER_BOX + i];
      if (c > 0) atom_add(&water[(b->j0 + j) * nx + (b->i0 + i)], c);
      b->count[j * WATER_BOX + i] = 0;
    }
  }
  water_box_clear_range(b);
}

#define WATER_BOX_ADD(i, j, share) box.count[((j) - box.j0) * WATER_BOX + ((i) - box.i0)] += (share)

__kernel void water_depth_scatter(const __global float* x, const __global float* z, const __global uint* id,
                                  const uint n, volatile __global long* water, const int tnx, const int tny,
                                  const float tcell) {
  const uint i = get_global_id(0);
  if (i >= n || (id[i] & DEAD_FLAG)) return;
  spread_quanta(water, tnx, tny, tcell, x[i], z[i], water_counts(tcell), 1, 0.5f, 0, 1.0f);
}

// The same counts, work-item g taking the particles [g·WATER_RUN, (g + 1)·WATER_RUN) into its box:
// the host takes this kernel where the water lies deep (several particles to a tile of the hash),
// water_depth_scatter where it runs as a sheet, whose particles have footprints of their own and
// would only pay for the box. Integer sums, so both give the same field.
__kernel void water_depth_scatter_runs(const __global float* x, const __global float* z, const __global uint* id,
                                       const uint n, volatile __global long* water, const int tnx, const int tny,
                                       const float tcell) {
  const uint first = get_global_id(0) * WATER_RUN;
  if (first >= n) return;
  const uint end = min(n, first + WATER_RUN);
  const long counts = water_counts(tcell);
  WaterBox box;
  for (int k = 0; k < WATER_BOX * WATER_BOX; ++k) box.count[k] = 0;
  box.i0 = box.j0 = -(1 << 20);  // holds no footprint until anchored
  water_box_clear_range(&box);
  for (uint i = first; i < end; ++i) {
    if (id[i] & DEAD_FLAG) continue;
    const Footprint f = footprint_of(x[i], z[i], tnx, tny, tcell);
    if (!(f.sum_x > 0.0f && f.sum_z > 0.0f)) {
      atom_add(&water[footprint_fallback_vertex(tnx, tny, tcell, x[i], z[i])], counts);
      continue;
    }
    if (!water_box_holds(&box, &f)) {
      water_box_flush(&box, water, tnx);
      water_box_anchor(&box, &f);
    }
    FOR_EACH_FOOTPRINT_SHARE(f, tnx, tcell, x[i], z[i], counts, 0.5f, (const __global float*)0, 1.0f, WATER_BOX_ADD);
    water_box_cover(&box, &f);
  }
  water_box_flush(&box, water, tnx);
}

__kernel void water_depth_gather(const __global float* x, const __global float* z, const __global uint* id,
                                 const uint n, const __global long* water, const int tnx, const int tny,
                                 const float tcell, __global float* depth) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  depth[i] = (id[i] & DEAD_FLAG) ? 0.0f : footprint_mean(water, WATER_QUANTUM, tnx, tny, tcell, x[i], z[i]);
}
