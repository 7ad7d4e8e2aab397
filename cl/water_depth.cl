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
// [2^l J, 2^l (J + 1)). Integer sums, so the levels are as independent of the order of the work-items
// as the fine field. `water` holds every level, the fine field (nx × ny) first, each after the one
// below. One launch builds them all: work-group g takes the block of fine vertices under the coarsest
// level's vertex g and sums it level by level in local memory (a launch per level cost more than
// the sums on a CPU's two cores: 6 of a step's 37 launches). FILM_LEVELS_MAX (host -D): the most
// levels, so a block is at most FILM_BLOCK_MAX fine vertices a side.
#define FILM_BLOCK_MAX (1 << FILM_LEVELS_MAX)
__kernel void water_depth_coarsen(__global long* water, const int nx, const int ny, const int levels) {
  __local long odd[(FILM_BLOCK_MAX / 2) * (FILM_BLOCK_MAX / 2)], even[(FILM_BLOCK_MAX / 4) * (FILM_BLOCK_MAX / 4)];
  int dims_x[FILM_LEVELS_MAX + 1], dims_y[FILM_LEVELS_MAX + 1];
  uint offset[FILM_LEVELS_MAX + 1];
  dims_x[0] = nx, dims_y[0] = ny, offset[0] = 0;
  for (int l = 1; l <= levels; ++l) {
    dims_x[l] = (dims_x[l - 1] + 1) / 2, dims_y[l] = (dims_y[l - 1] + 1) / 2;
    offset[l] = offset[l - 1] + (uint)(dims_x[l - 1] * dims_y[l - 1]);
  }
  const int item = get_local_id(0), items = get_local_size(0);
  const int block_x = get_group_id(0) % dims_x[levels], block_y = get_group_id(0) / dims_x[levels];
  for (int l = 1; l <= levels; ++l) {
    const int side = 1 << (levels - l);  // this level's vertices a side of the block
    __local long* out = l % 2 ? odd : even;
    const __local long* in = l % 2 ? even : odd;  // level l − 1's, 2·side a side (from level 2 on)
    for (int k = item; k < side * side; k += items) {
      const int i = k % side, j = k / side, I = block_x * side + i, J = block_y * side + j;
      long sum = 0;  // a vertex past the level's edge holds nothing for the level above
      if (I < dims_x[l] && J < dims_y[l]) {
        if (l == 1) {
          for (int fj = 2 * J; fj < min(2 * J + 2, ny); ++fj)
            for (int fi = 2 * I; fi < min(2 * I + 2, nx); ++fi) sum += water[fj * nx + fi];
        } else {
          for (int dj = 0; dj < 2; ++dj)
            for (int di = 0; di < 2; ++di) sum += in[(2 * j + dj) * (2 * side) + 2 * i + di];
        }
        water[offset[l] + J * dims_x[l] + I] = sum;
      }
      out[k] = sum;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
}

// water_depth_gather takes LANES particles a work-item (common.cl: its loops of varying length kept
// PoCL from vectorising it across work-items). Each lane runs footprint.cl's arithmetic in the same
// order as for one particle, a vertex beyond its own footprint adding an exact 0: the same bits as
// the scalar code it replaced.

// footprint_weight, lane by lane (a macro: no lane vector crosses a call, common.cl).
// SQUARE_V takes the bracket once as an argument, so it is computed once.
#define FOOTPRINT_WEIGHT_V(d) SQUARE_V(fmax(0.0f, 1.0f - (d) * (d) * (1.0f / (FOOTPRINT_RADIUS * FOOTPRINT_RADIUS))))
#define SQUARE_V(t) ((t) * (t))

// The water depth at (x, z) read on level l (nx × ny vertices, each the mean of the fine vertices of
// its block, standing at the block's centre) with the footprint scaled by 2^l, and the depth the
// particle's own water alone gives there: its volume over the footprint, V·Σ ŵ_k²/A_k, A_k the area
// of vertex k's block (cell_l², less where the block is cut by the grid's edge). Lane by lane;
// lanes outside `active` read vertex 0 and give nothing meaningful. (Each column's weight factor
// and fine vertices once, not once a row: the divisions were most of the films' reading time.)
inline void level_reading_v(const __global long* field, int l, int fnx, int fny, int nx, int ny, float fcell,
                            const floatv* px, const floatv* pz, const intv* pactive, floatv* depth, floatv* own) {
  const floatv x = *px, z = *pz;
  const intv active = *pactive;
  const int span = 1 << l;
  const float cell = fcell * (float)span, radius = FOOTPRINT_RADIUS * (float)span;
  const floatv lx = x - 0.5f * (float)(span - 1) * fcell, lz = z - 0.5f * (float)(span - 1) * fcell;
  const intv i0 = max(0, CONVERT_INTV(ceil((lx - radius) / cell)));
  const intv i1 = min(nx - 1, CONVERT_INTV(floor((lx + radius) / cell)));
  const intv j0 = max(0, CONVERT_INTV(ceil((lz - radius) / cell)));
  const intv j1 = min(ny - 1, CONVERT_INTV(floor((lz + radius) / cell)));
  floatv column_weight[FOOTPRINT_SIDE];
  intv column_cover[FOOTPRINT_SIDE];
  for (int a = 0; a < FOOTPRINT_SIDE; ++a) {
    const intv i = i0 + a;
    const floatv fi = CONVERT_FLOATV(i);
    column_weight[a] = fmax(0.0f, 1.0f - (fi * cell - lx) * (fi * cell - lx) / (radius * radius));
    column_cover[a] = min(fnx, span * (i + 1)) - span * i;
  }
  floatv sum = 0.0f, weights = 0.0f, squares = 0.0f;
  for (int b = 0; b < FOOTPRINT_SIDE; ++b) {
    const intv j = j0 + b;
    const intv row = active & (j <= j1);
    if (!any(row)) break;
    const floatv fj = CONVERT_FLOATV(j);
    const floatv t = fmax(0.0f, 1.0f - (fj * cell - lz) * (fj * cell - lz) / (radius * radius));
    const intv cover_z = min(fny, span * (j + 1)) - span * j;
    for (int a = 0; a < FOOTPRINT_SIDE; ++a) {
      const intv in = row & (i0 + a <= i1);
      const floatv u = column_weight[a];
      const floatv w = select((floatv)0.0f, t * t * u * u, in);
      const floatv covered = select((floatv)1.0f, CONVERT_FLOATV(column_cover[a] * cover_z), in);
      const intv vertex = select((intv)0, j * nx + i0 + a, in);
      const floatv count = LONGV_TO_FLOATV(GATHER_LONG(field, vertex));
      sum += w * select((floatv)0.0f, count, in) / covered;
      weights += w;
      squares += w * w / covered;
    }
  }
  const intv some = weights > 0.0f;
  *depth = select((floatv)0.0f, sum * WATER_QUANTUM / weights, some);
  *own = select((floatv)0.0f, WATER_PARTICLE_VOLUME * squares / (weights * weights * fcell * fcell), some);
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
  const uint first = get_global_id(0) * LANES;
  if (first >= n) return;
  const intv present = (intv)(int)(n - first) > LANE_INDEX;
  const intv k = select((intv)(int)first, (int)first + LANE_INDEX, present);  // the last work-item's spare lanes
  const floatv px = GATHER_FLOAT(x, k), pz = GATHER_FLOAT(z, k);
  const uintv flags = GATHER_UINT(id, k);
  const intv live = present & (CONVERT_INTV(flags & DEAD_FLAG) == 0);
  // The footprint (footprint_of), the fine field's footprint mean, and the depth the particle's own
  // water alone gives on it, V·Σŵ²/cell² (the weights are separable, and so is the sum of their
  // squares).
  const intv i0 = max(0, CONVERT_INTV(ceil((px - FOOTPRINT_RADIUS) / tcell)));
  const intv i1 = min(tnx - 1, CONVERT_INTV(floor((px + FOOTPRINT_RADIUS) / tcell)));
  const intv j0 = max(0, CONVERT_INTV(ceil((pz - FOOTPRINT_RADIUS) / tcell)));
  const intv j1 = min(tny - 1, CONVERT_INTV(floor((pz + FOOTPRINT_RADIUS) / tcell)));
  floatv sum_x = 0.0f, sum_z = 0.0f, squares_x = 0.0f, squares_z = 0.0f;
  for (int a = 0; a < FOOTPRINT_SIDE; ++a) {
    const floatv wx = select((floatv)0.0f, FOOTPRINT_WEIGHT_V(CONVERT_FLOATV(i0 + a) * tcell - px), i0 + a <= i1);
    const floatv wz = select((floatv)0.0f, FOOTPRINT_WEIGHT_V(CONVERT_FLOATV(j0 + a) * tcell - pz), j0 + a <= j1);
    sum_x += wx;
    sum_z += wz;
    squares_x += wx * wx;
    squares_z += wz * wz;
  }
  const intv reaches = live & (sum_x > 0.0f) & (sum_z > 0.0f);
  floatv sum = 0.0f;
  for (int b = 0; b < FOOTPRINT_SIDE; ++b) {
    const intv row = reaches & (j0 + b <= j1);
    if (!any(row)) break;
    const floatv wz = FOOTPRINT_WEIGHT_V(CONVERT_FLOATV(j0 + b) * tcell - pz);
    for (int a = 0; a < FOOTPRINT_SIDE; ++a) {
      const intv in = row & (i0 + a <= i1);
      const floatv w = select((floatv)0.0f, wz * FOOTPRINT_WEIGHT_V(CONVERT_FLOATV(i0 + a) * tcell - px), in);
      const intv vertex = select((intv)0, (j0 + b) * tnx + i0 + a, in);
      const floatv count = LONGV_TO_FLOATV(GATHER_LONG(water, vertex));
      sum += w * select((floatv)0.0f, count, in);
    }
  }
  const floatv fine = select((floatv)0.0f, sum * WATER_QUANTUM / (sum_x * sum_z), reaches);
  const floatv own_fine = select(
      (floatv)0.0f, WATER_PARTICLE_VOLUME * squares_x * squares_z / (sum_x * sum_x * sum_z * sum_z * tcell * tcell),
      reaches);
  floatv d = fine;
  intv searching = live & (fine < (FILM_NEIGHBOURS + 1.0f) * own_fine);
  if (levels > 0 && any(searching)) {
    uint offset = 0;
    int nx = tnx, ny = tny;
    for (int l = 1; l <= levels; ++l) {
      offset += (uint)(nx * ny);
      nx = (nx + 1) / 2;
      ny = (ny + 1) / 2;
      floatv r_depth, r_own;
      level_reading_v(water + offset, l, tnx, tny, nx, ny, tcell, &px, &pz, &searching, &r_depth, &r_own);
      const intv found = searching & (r_depth - r_own >= FILM_NEIGHBOURS * r_own);
      d = select(d, r_depth - r_own, found);
      searching &= ~found;
      if (!any(searching)) break;
    }
  }
  d = select((floatv)0.0f, d, live);
  float out[LANES];
  STOREV(d, 0, out);
  const int count = min((int)LANES, (int)(n - first));
  for (int l = 0; l < count; ++l) depth[first + l] = out[l];
}
