// SPDX-License-Identifier: MIT
// Particle droplets (Beyer 2015; models.md "droplet"). A batch of droplets moves in lockstep, each
// step in three stages: droplet_move moves every droplet one cell over the terrain as the previous
// step left it and writes down what it erodes or deposits; droplet_bin lists the droplets with
// changes by the block of DROPLET_BLOCK_ROWS rows and DROPLET_BLOCK_WIDTH columns of cells they are
// in (DropletBlocks: whole rows of the map on a CPU); droplet_apply then adds the changes to the
// fixed-point heights (counts of the height quantum), one work-item a block, in a launch for each
// parity of the blocks' column and row. What a droplet changes lies within its brush's reach (and
// a cell beyond) of its cell, and blocks are at least twice that reach plus one wide and high, so
// two blocks of one launch never touch the same vertex: plain integer adds, no atomics, and since
// integer sums do not depend on their order, neither does the result. (With 64-bit atomics
// straight from each droplet, 28 lock-prefixed adds a step, the adds took more time than the
// rest of the model.) Nothing writes the heights while the droplets read them, and they read the
// fixed heights themselves (as the float view would give them): the float view is refreshed once
// per batch, not once per step. Sediment is carried as quanta too: what a droplet erodes, it
// deposits (or carries out of the map, booked as outflow) exactly.
// (Running each droplet's whole lifetime on the terrain of the batch start let the droplets that
// met in one pit each fill it to the brim; the spikes that made grew without bound.)
// Per step, with cell coordinates and bilinear height and gradient:
//   dir = dir·inertia − grad·(1 − inertia), normalised; move one cell; Δh = h_new − h_old
//   capacity = max(−Δh · speed · water · capacity_factor, min_capacity)
//   uphill (Δh > 0): deposit min(Δh, sediment); over capacity: deposit (sediment − capacity)·deposit_speed
//   else erode min((capacity − sediment)·erode_speed, −Δh) with a radius brush
//   speed = sqrt(max(0, speed² − Δh·gravity)); water *= 1 − evaporate_speed
// Compile-time constants (host -D): DROPLET_*.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#define DROPLET_STREAM 0x64726f70UL  // "drop"
#define DROPLET_MASK_STREAM 0x64726d6bUL  // "drmk"

// fixed_height_view (common.cl), lane by lane, of a named longv: the same expression, the same
// bits. A macro: no lane vector crosses a call (common.cl).
#define FIXED_HEIGHT_VIEW_V(h, quantum) \
  (LONGV_TO_FLOATV((h) >> 20) * ((quantum) * 1048576.0f) + LONGV_TO_FLOATV((h) - (((h) >> 20) << 20)) * (quantum))

// Bilinear height (m) and gradient at (x, z), from the fixed heights as the float view gives them;
// lanes outside `valid` read vertex 0 and give nothing meaningful. The lanes come in and go out
// through pointers (common.cl).
inline void height_at(const __global long* h, float quantum, int nx, const floatv* px, const floatv* pz,
                      const intv* valid, floatv* height, floatv* gx, floatv* gz) {
  const floatv x = *px, z = *pz;
  const intv i = CONVERT_INTV(x), j = CONVERT_INTV(z);
  const floatv u = x - CONVERT_FLOATV(i), v = z - CONVERT_FLOATV(j);
  const intv k00 = select((intv)0, j * nx + i, *valid);
  const intv k10 = k00 + 1, k01 = k00 + nx, k11 = k00 + nx + 1;
  const longv f00 = GATHER_LONG(h, k00), f10 = GATHER_LONG(h, k10), f01 = GATHER_LONG(h, k01),
              f11 = GATHER_LONG(h, k11);
  const floatv h00 = FIXED_HEIGHT_VIEW_V(f00, quantum), h10 = FIXED_HEIGHT_VIEW_V(f10, quantum),
               h01 = FIXED_HEIGHT_VIEW_V(f01, quantum), h11 = FIXED_HEIGHT_VIEW_V(f11, quantum);
  *gx = (h10 - h00) * (1.0f - v) + (h11 - h01) * v;
  *gz = (h01 - h00) * (1.0f - u) + (h11 - h10) * u;
  *height = h00 * (1.0f - u) * (1.0f - v) + h10 * u * (1.0f - v) + h01 * (1.0f - u) * v + h11 * u * v;
}

// Deposits `quanta` on the 4 corners of the cell with bilinear weights, exactly.
inline void deposit_bilinear(__global long* height_fixed, __global uint* changed, int tiles_x, int nx, float x, float z,
                             long quanta) {
  if (quanta <= 0) return;
  const int i = (int)x, j = (int)z;
  mark_changed_tiles(changed, tiles_x, i, i + 1, j, j + 1);
  const float u = x - (float)i, v = z - (float)j;
  const float w[4] = {(1.0f - u) * (1.0f - v), u * (1.0f - v), (1.0f - u) * v, u * v};
  const int k[4] = {j * nx + i, j * nx + i + 1, (j + 1) * nx + i, (j + 1) * nx + i + 1};
  long given = 0;
  int largest = 0;
  for (int c = 0; c < 4; ++c) {
    const long part = min((long)floor((float)quanta * w[c]), quanta - given);
    given += part;
    if (w[c] > w[largest]) largest = c;
    if (part > 0) height_fixed[k[c]] += part;
  }
  if (quanta - given > 0) height_fixed[k[largest]] += quanta - given;
}

// The erosion brush: the vertices within DROPLET_RADIUS cells of (x, z), weighted by
// (radius − distance)·e, with e the vertex's erodibility (1 without a layer stack). A layered bed
// gives in proportion to how easily it erodes, a frozen vertex nothing (docs/layers.md).
#define BRUSH_SIDE (2 * (int)DROPLET_RADIUS_CELLS + 2)
typedef struct {
  int ci, cj;          // the droplet's cell
  int i0, i1, j0, j1;  // the brush's columns and rows, relative to the cell
  float total;         // the sum of the weights
  float plain_total;   // the same with every erodibility 1
} Brush;

// Fills weight[] (BRUSH_SIDE² entries, row by row from (−r, −r)) and returns the brush's extent.
inline Brush brush_weights(int nx, int ny, float x, float z, const __global float* erodibility, float* weight) {
  const int r = DROPLET_RADIUS_CELLS;
  Brush b;
  b.ci = (int)x;
  b.cj = (int)z;
  // Only rows and columns of the map nearer than the radius can hold a weight: every vertex of
  // another lies at least the radius away, its weight is 0, and adding 0 to the sums changes no bit.
  // (A radius of 3 cells leaves 6 × 6 of the 8 × 8 vertices around the droplet's cell.)
  b.i0 = r + 1;
  b.i1 = -r - 1;
  b.j0 = r + 1;
  b.j1 = -r - 1;
  for (int d = -r; d <= r + 1; ++d) {
    const float dx = (float)(b.ci + d) - x, dz = (float)(b.cj + d) - z;
    if (b.ci + d >= 0 && b.ci + d < nx && sqrt(dx * dx) < DROPLET_RADIUS) {
      b.i0 = min(b.i0, d);
      b.i1 = max(b.i1, d);
    }
    if (b.cj + d >= 0 && b.cj + d < ny && sqrt(dz * dz) < DROPLET_RADIUS) {
      b.j0 = min(b.j0, d);
      b.j1 = max(b.j1, d);
    }
  }
  // The weights over the whole box, in loops of fixed length that the compiler vectorises; a vertex
  // outside the extent (or the map) weighs 0.
  float plain[BRUSH_SIDE * BRUSH_SIDE], erodible[BRUSH_SIDE * BRUSH_SIDE];
  for (int dj = 0; dj < BRUSH_SIDE; ++dj) {
    const int c = b.cj - r + dj;
    const float dz = (float)c - z;
    const bool row_in = dj - r >= b.j0 && dj - r <= b.j1;
    for (int di = 0; di < BRUSH_SIDE; ++di) {
      const int a = b.ci - r + di;
      const float dx = (float)a - x;  // sqrt, not hypot: far faster on CPUs
      const bool in = row_in && di - r >= b.i0 && di - r <= b.i1;
      const float w = in ? fmax(0.0f, DROPLET_RADIUS - sqrt(dx * dx + dz * dz)) : 0.0f;
      const float e = in ? ERODIBILITY(erodibility, c * nx + a) : 0.0f;
      plain[dj * BRUSH_SIDE + di] = w;
      erodible[dj * BRUSH_SIDE + di] = e;
      weight[dj * BRUSH_SIDE + di] = w * e;
    }
  }
  // The sums over the extent in the order of the rows, the weighted one as multiply-adds: the bits
  // the brush always gave. Without a layer stack every e is 1 and the two sums are one.
  b.total = 0.0f;
  b.plain_total = 0.0f;
  for (int dj = b.j0 + r; dj <= b.j1 + r; ++dj) {
    for (int di = b.i0 + r; di <= b.i1 + r; ++di) {
      if (GROUND) b.total += plain[dj * BRUSH_SIDE + di] * erodible[dj * BRUSH_SIDE + di];
      b.plain_total += plain[dj * BRUSH_SIDE + di];
    }
  }
  if (!GROUND) b.total = b.plain_total;
  return b;
}

// Whether the brush's mean erodibility is exactly 1 and it always reaches a vertex: no layer stack,
// and a radius above √½, which reaches the nearest corner of the droplet's cell. (A conditional, not
// a logical operator, between the two constants: the compiler warns of `&&` on a constant.)
#define PLAIN_BRUSH ((GROUND ? 0.0f : DROPLET_RADIUS) > 0.75f)

// The quanta the brush takes for `amount` m of erosion: floor(amount·ē/quantum), with ē the mean
// erodibility under the brush.
inline long brush_quanta(int nx, int ny, float x, float z, float amount, float quantum,
                         const __global float* erodibility) {
  // A plain brush's ē is exactly 1: the weights need not be computed (the same quanta, bit for bit).
  if (PLAIN_BRUSH) return (long)floor(amount / quantum);
  float weight[BRUSH_SIDE * BRUSH_SIDE];
  const Brush b = brush_weights(nx, ny, x, z, erodibility, weight);
  // ē of a brush whose every erodibility is 1 is 1 on any device (a GPU's division need not give x/x = 1).
  const float mean = b.total == b.plain_total ? 1.0f : b.total / b.plain_total;
  const long quanta = b.plain_total > 0.0f ? (long)floor(amount * mean / quantum) : 0;
  return b.total > 0.0f ? quanta : 0;
}

// Takes `quanta` (from brush_quanta) from the brush's vertices in proportion to their weights, exactly.
inline void erode_brush(__global long* height_fixed, __global uint* changed, int tiles_x, int nx, int ny,
                        float x, float z, long quanta, const __global float* erodibility) {
  if (quanta <= 0) return;
  const int r = DROPLET_RADIUS_CELLS;
  float weight[BRUSH_SIDE * BRUSH_SIDE];
  const Brush b = brush_weights(nx, ny, x, z, erodibility, weight);
  mark_changed_tiles(changed, tiles_x, b.ci + b.i0, b.ci + b.i1, b.cj + b.j0, b.cj + b.j1);
  // Each vertex's share of the quanta over the whole box (vectorised), then the running sum in the
  // order of the rows, which caps the last shares and gives the rest to the largest.
  long part[BRUSH_SIDE * BRUSH_SIDE];
  const float q = (float)quanta;
  for (int k = 0; k < BRUSH_SIDE * BRUSH_SIDE; ++k) {
    const float w = weight[k] / b.total;
    part[k] = weight[k] > 0.0f && w > 0.0f ? (long)floor(q * w) : -1;  // -1: no share (outside the disc, frozen)
  }
  long taken = 0, best_part = -1;
  int best = -1;
  for (int dj = b.j0 + r; dj <= b.j1 + r; ++dj) {
    for (int di = b.i0 + r; di <= b.i1 + r; ++di) {
      const long share = part[dj * BRUSH_SIDE + di];
      if (share < 0) continue;
      const int m = (b.cj - r + dj) * nx + (b.ci - r + di);
      const long given = min(share, quanta - taken);
      taken += given;
      if (given > best_part) {
        best_part = given;
        best = m;
      }
      if (given > 0) height_fixed[m] -= given;
    }
  }
  if (quanta - taken > 0 && best >= 0) height_fixed[best] -= quanta - taken;
}

// Droplet state between steps, one plane of `stride` floats per field (DROPLET_X .. DROPLET_WATER,
// in cell units); water < 0 marks a droplet that has finished. droplet_spawn places a batch's
// droplets; the host then stores them in the order of where they fell (row by row), and
// droplet_move and droplet_apply take droplet g with work-item g: neighbouring work-items then
// touch the same rows of the terrain, which stay in the cache, and read their states one after
// another. Droplets in the order they were drawn touched a random place each. The changes are
// integer sums, so the order changes nothing in the result. (Planes rather than six floats a
// droplet: adjacent fields made the compiler pair x with z in 2-wide vectors, which kept PoCL from
// running 8 droplets in the lanes of one vector.)
#define DROPLET_X 0
#define DROPLET_Z 1
#define DROPLET_DIR_X 2
#define DROPLET_DIR_Z 3
#define DROPLET_SPEED 4
#define DROPLET_WATER 5
#define FIELD(field) state[(field) * stride + d]

__kernel void droplet_spawn(const int nx, const int ny, const ulong seed, const ulong first_droplet, const uint count,
                            const uint stride, __global float* state, __global long* load,
                            volatile __global long* counters, const __global float* rain_weight, const float spawn_x,
                            const float spawn_z, const float spawn_radius) {
  const uint d = get_global_id(0);
  if (d >= count) return;
  const ulong id = first_droplet + d;
  if (spawn_radius > 0.0f) {  // painted rain (runnel-viewer): uniform on the disc, in cells
    const float r = spawn_radius * sqrt(rng_uniform(seed, DROPLET_STREAM, 2 * id));
    const float a = 6.2831853f * rng_uniform(seed, DROPLET_STREAM, 2 * id + 1);
    FIELD(DROPLET_X) = clamp(spawn_x + r * cos(a), 0.0f, (float)(nx - 1) - 1e-3f);
    FIELD(DROPLET_Z) = clamp(spawn_z + r * sin(a), 0.0f, (float)(ny - 1) - 1e-3f);
  } else {
    FIELD(DROPLET_X) = fmin(rng_uniform(seed, DROPLET_STREAM, 2 * id) * (float)(nx - 1), (float)(nx - 1) - 1e-3f);
    FIELD(DROPLET_Z) = fmin(rng_uniform(seed, DROPLET_STREAM, 2 * id + 1) * (float)(ny - 1), (float)(ny - 1) - 1e-3f);
  }
  FIELD(DROPLET_DIR_X) = 0.0f;
  FIELD(DROPLET_DIR_Z) = 0.0f;
  FIELD(DROPLET_SPEED) = DROPLET_INITIAL_SPEED;
  FIELD(DROPLET_WATER) = DROPLET_INITIAL_WATER;
  load[d] = 0;
#if RAIN_MASK
  // The rain mask: a droplet falls at its place with the probability the mask gives there
  // (docs/layers.md); one that does not fall finishes at once, having done nothing.
  const int spawn = (int)(FIELD(DROPLET_Z) + 0.5f) * nx + (int)(FIELD(DROPLET_X) + 0.5f);
  if (rng_uniform(seed, DROPLET_MASK_STREAM, id) >= rain_weight[spawn]) {
    FIELD(DROPLET_WATER) = -1.0f;
    atom_inc(&counters[2]);
  }
#endif
}

// One step of every droplet of the batch, on heights nobody writes during it; work-item w moves
// droplets LANES·w .. LANES·w + LANES − 1 (the planes hold whole vectors). What a
// droplet changes goes to its plan, two planes of `stride` for droplet_apply: the quanta deposited
// (> 0) or eroded with the brush (< 0) at its old place, and the quanta it deposits at its new
// place at the end of its life; the old place in plan_place's two. A droplet with changes counts
// itself in its block and keeps its block and its number there in plan_bin's two planes
// (NO_BLOCK: none). Lanes follow one droplet each through the branches as masks (−1: taken).
#define NO_BLOCK 0xffffffffu
__kernel void droplet_move(const __global long* height_fixed, const int nx, const int ny, const float quantum,
                           const uint count, const uint stride, const int step_index, __global float* state,
                           __global long* load, volatile __global long* counters, const __global float* erodibility,
                           __global float* plan_place, __global long* plan, __global uint* plan_bin,
                           volatile __global uint* block_count, const int blocks_x) {
  const uint w = get_global_id(0);
  if (w * LANES >= count) return;
  const uint first = w * LANES;
  const floatv x = LOADV(w, state + DROPLET_X * stride), z = LOADV(w, state + DROPLET_Z * stride);
  const floatv dir_x0 = LOADV(w, state + DROPLET_DIR_X * stride), dir_z0 = LOADV(w, state + DROPLET_DIR_Z * stride);
  const floatv speed0 = LOADV(w, state + DROPLET_SPEED * stride), water0 = LOADV(w, state + DROPLET_WATER * stride);
  const longv sediment0 = LOADV_LONG(w, load);
  const intv live = ((intv)(int)(count - first) > LANE_INDEX) & (water0 >= 0.0f);
  floatv h_old, gx, gz;
  height_at(height_fixed, quantum, nx, &x, &z, &live, &h_old, &gx, &gz);
  const floatv ux = dir_x0 * DROPLET_INERTIA - gx * (1.0f - DROPLET_INERTIA);
  const floatv uz = dir_z0 * DROPLET_INERTIA - gz * (1.0f - DROPLET_INERTIA);
  const floatv len = sqrt(ux * ux + uz * uz);
  const intv flat = live & (len == 0.0f);  // the droplet stops and deposits what it carries
  const floatv dir_x = ux / len, dir_z = uz / len;
  const floatv nx_pos = x + dir_x, nz_pos = z + dir_z;
  const intv out = live & ~flat &
                   ((nx_pos < 0.0f) | (nz_pos < 0.0f) | (nx_pos >= (float)(nx - 1)) | (nz_pos >= (float)(ny - 1)));
  const intv moves = live & ~flat & ~out;
  floatv h_new, gx2, gz2;
  height_at(height_fixed, quantum, nx, &nx_pos, &nz_pos, &moves, &h_new, &gx2, &gz2);
  const floatv dh = h_new - h_old;  // m
  const floatv capacity = fmax(-dh * speed0 * water0 * DROPLET_CAPACITY, DROPLET_MIN_CAPACITY);  // m of height
  const floatv carried = LONGV_TO_FLOATV(sediment0) * quantum;
  const intv deposits = moves & ((dh > 0.0f) | (carried > capacity));
  const intv erodes = moves & ~deposits;
  const floatv deposit_amount = select((carried - capacity) * DROPLET_DEPOSIT, fmin(dh, carried), dh > 0.0f);
  const longv deposit_quanta = FLOATV_TO_LONGV(floor(deposit_amount / quantum));
  const longv deposited = MAX_LONGV((longv)0, MIN_LONGV(sediment0, deposit_quanta));
  const floatv erode_amount = fmin((capacity - carried) * DROPLET_ERODE, -dh);
  const longv erode_quanta = FLOATV_TO_LONGV(floor(erode_amount / quantum));
  longv taken = MAX_LONGV((longv)0, erode_quanta);
  if (!PLAIN_BRUSH) {  // the brush's weights decide: one lane at a time
    long t[LANES];
    int e[LANES];
    float px[LANES], pz[LANES], amount[LANES];
    STOREV(erodes, 0, e);
    STOREV(x, 0, px);
    STOREV(z, 0, pz);
    STOREV(erode_amount, 0, amount);
    for (int l = 0; l < LANES; ++l)
      t[l] = e[l] ? max(0L, brush_quanta(nx, ny, px[l], pz[l], amount[l], quantum, erodibility)) : 0;
    taken = LOADV_LONG(0, t);
  }
  // The new state of each kind of lane; a finished or missing droplet keeps its own.
  const longv lmoves = INTV_TO_LONGV(moves), ldeposits = INTV_TO_LONGV(deposits), lerodes = INTV_TO_LONGV(erodes);
  const longv lflat = INTV_TO_LONGV(flat), lout = INTV_TO_LONGV(out);
  longv change = SELECT_LONGV((longv)0, deposited, ldeposits);
  change = SELECT_LONGV(change, -taken, lerodes);
  change = SELECT_LONGV(change, sediment0, lflat);
  longv sediment = SELECT_LONGV(sediment0, sediment0 - deposited, ldeposits);
  sediment = SELECT_LONGV(sediment, sediment0 + taken, lerodes);
  sediment = SELECT_LONGV(sediment, (longv)0, lflat | lout);
  const floatv speed = select(speed0, sqrt(fmax(0.0f, speed0 * speed0 - dh * DROPLET_GRAVITY)), moves);
  floatv water = select(water0, water0 * (1.0f - DROPLET_EVAPORATE), moves);
  water = select(water, (floatv)(-1.0f), flat | out);
  longv final_deposit = (longv)0;
  if (step_index == DROPLET_LIFETIME - 1) {  // the end of its life: it deposits what it still carries
    final_deposit = SELECT_LONGV((longv)0, sediment, lmoves);
    sediment = SELECT_LONGV(sediment, (longv)0, lmoves);
    water = select(water, (floatv)(-1.0f), moves);
  }
  STOREV(select(x, nx_pos, moves), w, state + DROPLET_X * stride);
  STOREV(select(z, nz_pos, moves), w, state + DROPLET_Z * stride);
  STOREV(select(dir_x0, dir_x, moves), w, state + DROPLET_DIR_X * stride);
  STOREV(select(dir_z0, dir_z, moves), w, state + DROPLET_DIR_Z * stride);
  STOREV(speed, w, state + DROPLET_SPEED * stride);
  STOREV(water, w, state + DROPLET_WATER * stride);
  STOREV_LONG(sediment, w, load);
  STOREV_LONG(change, w, plan);
  STOREV_LONG(final_deposit, w, plan + stride);
  STOREV(x, w, plan_place);
  STOREV(z, w, plan_place + stride);
  // Atomics, one lane at a time: the outflow counters, and each droplet's place in its block.
  const intv busy = (LONGV_TO_INTV(change != 0) | LONGV_TO_INTV(final_deposit != 0)) & live;
  const uintv block =
      CONVERT_UINTV((CONVERT_INTV(z) / DROPLET_BLOCK_ROWS) * blocks_x + CONVERT_INTV(x) / DROPLET_BLOCK_WIDTH);
  int is_out[LANES], is_busy[LANES];
  long carried_out[LANES];
  uint blocks[LANES], bin[2 * LANES];
  STOREV(out, 0, is_out);
  STOREV(busy, 0, is_busy);
  STOREV_LONG(sediment0, 0, carried_out);
  STOREV(block, 0, blocks);
  for (int l = 0; l < LANES; ++l) {
    if (is_out[l]) {
      atom_add(&counters[1], carried_out[l]);  // carried out of the map
      atom_inc(&counters[0]);
    }
    bin[l] = is_busy[l] ? blocks[l] : NO_BLOCK;
    bin[LANES + l] = is_busy[l] ? atomic_inc(&block_count[blocks[l]]) : 0;
  }
  STOREV(LOADV(0, bin), w, plan_bin);
  STOREV(LOADV(1, bin), w, plan_bin + stride);
}

// Lists the droplets with changes by block: block_start from block_count (an exclusive prefix sum),
// then droplet d at block_start[its block] + its number there. One work-group of
// DROPLET_BIN_GROUP work-items; the order within a block is the order droplet_move's atomics gave,
// which changes no sum.
__kernel void droplet_bin(const uint blocks, const __global uint* block_count, __global uint* block_start,
                          const uint count, const uint stride, const __global uint* plan_bin,
                          __global uint* block_list) {
  __local uint sums[DROPLET_BIN_GROUP + 1];
  const uint lid = get_local_id(0);
  group_exclusive_scan(block_count, block_start, blocks, sums);
  barrier(CLK_GLOBAL_MEM_FENCE);
  for (uint d = lid; d < count; d += DROPLET_BIN_GROUP) {
    const uint block = plan_bin[d];
    if (block != NO_BLOCK) block_list[block_start[block] + plan_bin[stride + d]] = d;
  }
}

// The changes droplet_move planned for the droplets of one block, added to the fixed heights; the
// blocks of one launch have the column and row parity `parity` (0..3), so none touches another's
// vertices. A droplet's state holds its new place. The block's count is cleared for the next step.
__kernel void droplet_apply(__global long* height_fixed, __global uint* changed, const int tiles_x, const int nx,
                            const int ny, const uint stride, const __global float* state,
                            const __global float* erodibility, const __global float* plan_place,
                            const __global long* plan, const __global uint* block_start, __global uint* block_count,
                            const __global uint* block_list, const int blocks_x, const int blocks_y,
                            const int parity) {
  const int g = get_global_id(0);
  const int half_x = (blocks_x + 1) / 2;
  const int bx = 2 * (g % half_x) + (parity & 1), by = 2 * (g / half_x) + (parity >> 1);
  if (bx >= blocks_x || by >= blocks_y) return;
  const int block = by * blocks_x + bx;
  const uint first = block_start[block], n = block_count[block];
  block_count[block] = 0;
  for (uint k = first; k < first + n; ++k) {
    const uint d = block_list[k];
    const long change = plan[d], final_deposit = plan[stride + d];
    const float x = plan_place[d], z = plan_place[stride + d];
    if (change > 0) deposit_bilinear(height_fixed, changed, tiles_x, nx, x, z, change);
    if (change < 0) erode_brush(height_fixed, changed, tiles_x, nx, ny, x, z, -change, erodibility);
    deposit_bilinear(height_fixed, changed, tiles_x, nx, FIELD(DROPLET_X), FIELD(DROPLET_Z), final_deposit);
  }
}
