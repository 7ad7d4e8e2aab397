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
// WATER_RUN, FILM_NEIGHBOURS.

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

// The water on coarser grids, for films (docs/erosion.md, "Films"): level l has vertices 2^l cells
// apart, vertex (I, J) holding the sum of the counts on the fine vertices [2^l I, 2^l (I + 1)) ×
// [2^l J, 2^l (J + 1)), built from the level below. Integer sums, so the levels are as
// independent of the order of the work-items as the fine field. `levels` holds every level, the
// fine field first, each after the one below.
__kernel void water_depth_coarsen(__global long* levels, const uint fine_offset, const int fnx, const int fny,
                                  const uint coarse_offset, const int cnx, const int cny) {
  const int k = get_global_id(0);
  if (k >= cnx * cny) return;
  const int I = k % cnx, J = k / cnx;
  long sum = 0;
  for (int j = 2 * J; j < min(2 * J + 2, fny); ++j)
    for (int i = 2 * I; i < min(2 * I + 2, fnx); ++i) sum += levels[fine_offset + j * fnx + i];
  levels[coarse_offset + J * cnx + I] = sum;
}

// The water depth at (x, z) read on level l (nx × ny vertices, each the mean of the fine vertices of
// its block, standing at the block's centre) with the footprint scaled by 2^l, and the depth the
// particle's own water alone gives there: its volume over the footprint, V·Σ ŵ_k²/A_k, A_k the area
// of vertex k's block (cell_l², less where the block is cut by the grid's edge).
typedef struct {
  float depth, own;
} LevelReading;

inline LevelReading level_reading(const __global long* field, int l, int fnx, int fny, int nx, int ny, float fcell,
                                  float x, float z) {
  const int span = 1 << l;
  const float cell = fcell * (float)span, radius = FOOTPRINT_RADIUS * (float)span;
  const float lx = x - 0.5f * (float)(span - 1) * fcell, lz = z - 0.5f * (float)(span - 1) * fcell;
  const int i0 = max(0, (int)ceil((lx - radius) / cell)), i1 = min(nx - 1, (int)floor((lx + radius) / cell));
  const int j0 = max(0, (int)ceil((lz - radius) / cell)), j1 = min(ny - 1, (int)floor((lz + radius) / cell));
  // Each column's weight factor and fine vertices once, not once a row: the divisions were most of
  // the films' reading time.
  float column_weight[FOOTPRINT_SIDE];
  int column_cover[FOOTPRINT_SIDE];
  for (int i = i0; i <= i1; ++i) {
    column_weight[i - i0] = fmax(0.0f, 1.0f - ((float)i * cell - lx) * ((float)i * cell - lx) / (radius * radius));
    column_cover[i - i0] = min(fnx, span * (i + 1)) - span * i;
  }
  float sum = 0.0f, weights = 0.0f, squares = 0.0f;
  for (int j = j0; j <= j1; ++j) {
    const float t = fmax(0.0f, 1.0f - ((float)j * cell - lz) * ((float)j * cell - lz) / (radius * radius));
    const int cover_z = min(fny, span * (j + 1)) - span * j;
    for (int i = i0; i <= i1; ++i) {
      const float u = column_weight[i - i0];
      const float w = t * t * u * u;
      const float covered = (float)(column_cover[i - i0] * cover_z);  // fine vertices: fewer at the far edges
      sum += w * (float)field[j * nx + i] / covered;
      weights += w;
      squares += w * w / covered;
    }
  }
  LevelReading r = {0.0f, 0.0f};
  if (weights > 0.0f) {
    r.depth = sum * WATER_QUANTUM / weights;
    r.own = WATER_PARTICLE_VOLUME * squares / (weights * weights * fcell * fcell);
  }
  return r;
}

// The depth a particle's own water alone gives on its fine footprint f, V·Σŵ²/cell²: the weights
// are separable, and so is the sum of their squares (cheap enough to ask of every particle).
inline float own_fine_depth(const Footprint* f, float x, float z, float cell) {
  if (!(f->sum_x > 0.0f && f->sum_z > 0.0f)) return 0.0f;
  float squares_x = 0.0f, squares_z = 0.0f;
  for (int i = f->i0; i <= f->i1; ++i) {
    const float w = footprint_weight((float)i * cell - x);
    squares_x += w * w;
  }
  for (int j = f->j0; j <= f->j1; ++j) {
    const float w = footprint_weight((float)j * cell - z);
    squares_z += w * w;
  }
  return WATER_PARTICLE_VOLUME * squares_x * squares_z / (f->sum_x * f->sum_x * f->sum_z * f->sum_z * cell * cell);
}

// D at each particle. Where the water is resolved (the footprint holds FILM_NEIGHBOURS particles'
// water besides the particle's own) the fine field's footprint mean, the particle's own water
// included: it is one of a column of water. A film's footprint holds too little water to tell the
// depth from the particle's own: it is read on the finest coarser level whose footprint holds
// FILM_NEIGHBOURS other particles' water, without its own (the particles of a film lie at random, and
// a footprint centred on one of them would count it on top of the mean: the k-nearest-neighbour
// estimate, (k − 1)/area). Where no level holds that much, the particle is not a sample of a sheet
// but a drop on its own (the first drops of a storm, a test droplet), as deep as its own footprint
// says: the fine mean again.
__kernel void water_depth_gather(const __global float* x, const __global float* z, const __global uint* id,
                                 const uint n, const __global long* water, const int tnx, const int tny,
                                 const float tcell, const int levels, __global float* depth) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  if (id[i] & DEAD_FLAG) {
    depth[i] = 0.0f;
    return;
  }
  const Footprint f = footprint_of(x[i], z[i], tnx, tny, tcell);
  const float fine = footprint_mean(&f, water, WATER_QUANTUM, tnx, tcell, x[i], z[i]);
  float d = fine;
  if (levels > 0 && fine < (FILM_NEIGHBOURS + 1.0f) * own_fine_depth(&f, x[i], z[i], tcell)) {
    uint offset = 0;
    int nx = tnx, ny = tny;
    for (int l = 1; l <= levels; ++l) {
      offset += (uint)(nx * ny);
      nx = (nx + 1) / 2;
      ny = (ny + 1) / 2;
      const LevelReading r = level_reading(water + offset, l, tnx, tny, nx, ny, tcell, x[i], z[i]);
      if (r.depth - r.own >= FILM_NEIGHBOURS * r.own) {
        d = r.depth - r.own;
        break;
      }
    }
  }
  depth[i] = d;
}
