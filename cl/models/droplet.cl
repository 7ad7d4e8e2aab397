// SPDX-License-Identifier: MIT
// Particle droplets (Beyer 2015; models.md "droplet"). A batch of droplets moves in lockstep, each
// step in two launches: droplet_move moves every droplet one cell over the terrain as the previous
// step left it and writes down what it erodes or deposits; droplet_apply then adds those changes to
// the fixed-point heights (counts of the height quantum) with 64-bit integer atomics, so a step's
// result does not depend on the order of the droplets. Nothing writes the heights while the droplets
// read them, and they read the fixed heights themselves (as the float view would give them): the
// float view is refreshed once per batch, not once per step. Sediment is carried as quanta too:
// what a droplet erodes, it deposits (or carries out of the map, booked as outflow) exactly.
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

// Bilinear height (m) and gradient at (x, z), from the fixed heights as the float view gives them.
inline float height_at(const __global long* h, float quantum, int nx, float x, float z, float* gx, float* gz) {
  const int i = (int)x, j = (int)z;
  const float u = x - (float)i, v = z - (float)j;
  const int k = j * nx + i;
  const float h00 = fixed_height_view(h[k], quantum), h10 = fixed_height_view(h[k + 1], quantum),
              h01 = fixed_height_view(h[k + nx], quantum), h11 = fixed_height_view(h[k + nx + 1], quantum);
  *gx = (h10 - h00) * (1.0f - v) + (h11 - h01) * v;
  *gz = (h01 - h00) * (1.0f - u) + (h11 - h10) * u;
  return h00 * (1.0f - u) * (1.0f - v) + h10 * u * (1.0f - v) + h01 * (1.0f - u) * v + h11 * u * v;
}

// Deposits `quanta` on the 4 corners of the cell with bilinear weights, exactly.
inline void deposit_bilinear(volatile __global long* height_fixed, __global uint* changed, int tiles_x, int nx, float x,
                             float z, long quanta) {
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
    if (part > 0) atom_add(&height_fixed[k[c]], part);
  }
  if (quanta - given > 0) atom_add(&height_fixed[k[largest]], quanta - given);
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

// The quanta the brush takes for `amount` m of erosion: floor(amount·ē/quantum), with ē the mean
// erodibility under the brush.
inline long brush_quanta(int nx, int ny, float x, float z, float amount, float quantum,
                         const __global float* erodibility) {
  // Every erodibility 1 makes ē exactly 1, and a radius above √½ always reaches the nearest corner
  // of the droplet's cell: then the weights need not be computed here (the same quanta, bit for bit).
  if (!GROUND && DROPLET_RADIUS > 0.75f) return (long)floor(amount / quantum);
  float weight[BRUSH_SIDE * BRUSH_SIDE];
  const Brush b = brush_weights(nx, ny, x, z, erodibility, weight);
  const long quanta = b.plain_total > 0.0f ? (long)floor(amount * (b.total / b.plain_total) / quantum) : 0;
  return b.total > 0.0f ? quanta : 0;
}

// Takes `quanta` (from brush_quanta) from the brush's vertices in proportion to their weights, exactly.
inline void erode_brush(volatile __global long* height_fixed, __global uint* changed, int tiles_x, int nx, int ny,
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
      if (given > 0) atom_add(&height_fixed[m], -given);
    }
  }
  if (quanta - taken > 0 && best >= 0) atom_add(&height_fixed[best], -(quanta - taken));
}

// Droplet state between steps: (x, z, dir_x, dir_z, speed, water) in cell units; water < 0 marks
// a droplet that has finished. droplet_spawn places a batch's droplets; the host then stores them
// in the order of where they fell (row by row), and droplet_move and droplet_apply take droplet g with work-item g:
// neighbouring work-items then touch the same rows of the terrain, which stay in the cache, and
// read their states one after another. Droplets in the order they were drawn touched a random
// place each. The changes are integer sums, so the order changes nothing in the result.
__kernel void droplet_spawn(const int nx, const int ny, const ulong seed, const ulong first_droplet, const uint count,
                            __global float* state, __global long* load, volatile __global long* counters,
                            const __global float* rain_weight, const float spawn_x, const float spawn_z,
                            const float spawn_radius) {
  const uint d = get_global_id(0);
  if (d >= count) return;
  __global float* s = state + 6 * d;
  const ulong id = first_droplet + d;
  if (spawn_radius > 0.0f) {  // painted rain (runnel-viewer): uniform on the disc, in cells
    const float r = spawn_radius * sqrt(rng_uniform(seed, DROPLET_STREAM, 2 * id));
    const float a = 6.2831853f * rng_uniform(seed, DROPLET_STREAM, 2 * id + 1);
    s[0] = clamp(spawn_x + r * cos(a), 0.0f, (float)(nx - 1) - 1e-3f);
    s[1] = clamp(spawn_z + r * sin(a), 0.0f, (float)(ny - 1) - 1e-3f);
  } else {
    s[0] = fmin(rng_uniform(seed, DROPLET_STREAM, 2 * id) * (float)(nx - 1), (float)(nx - 1) - 1e-3f);
    s[1] = fmin(rng_uniform(seed, DROPLET_STREAM, 2 * id + 1) * (float)(ny - 1), (float)(ny - 1) - 1e-3f);
  }
  s[2] = 0.0f;
  s[3] = 0.0f;
  s[4] = DROPLET_INITIAL_SPEED;
  s[5] = DROPLET_INITIAL_WATER;
  load[d] = 0;
#if RAIN_MASK
  // The rain mask: a droplet falls at its place with the probability the mask gives there
  // (docs/layers.md); one that does not fall finishes at once, having done nothing.
  const int spawn = (int)(s[1] + 0.5f) * nx + (int)(s[0] + 0.5f);
  if (rng_uniform(seed, DROPLET_MASK_STREAM, id) >= rain_weight[spawn]) {
    s[5] = -1.0f;
    atom_inc(&counters[2]);
  }
#endif
}

// One step of every droplet of the batch, on heights nobody writes during it. What the droplet
// changes goes to its plan, for droplet_apply: at its old place, `change.x` quanta deposited (> 0) or
// eroded with the brush (< 0); at its new place, `change.y` quanta deposited at the end of its life.
__kernel void droplet_move(const __global long* height_fixed, const int nx, const int ny, const float quantum,
                           const uint count, const int step_index, __global float* state, __global long* load,
                           volatile __global long* counters, const __global float* erodibility,
                           __global float2* plan_place, __global long2* plan_change) {
  const uint d = get_global_id(0);
  if (d >= count) return;
  __global float* s = state + 6 * d;
  plan_change[d] = (long2)(0, 0);
  if (s[5] < 0.0f) return;
  float x = s[0], z = s[1], speed = s[4], water = s[5];
  long sediment = load[d];  // quanta of height
  plan_place[d] = (float2)(x, z);
  float gx, gz;
  const float h_old = height_at(height_fixed, quantum, nx, x, z, &gx, &gz);
  float dir_x = s[2] * DROPLET_INERTIA - gx * (1.0f - DROPLET_INERTIA);
  float dir_z = s[3] * DROPLET_INERTIA - gz * (1.0f - DROPLET_INERTIA);
  const float len = sqrt(dir_x * dir_x + dir_z * dir_z);
  if (len == 0.0f) {  // flat: the droplet stops and deposits what it carries
    plan_change[d] = (long2)(sediment, 0);
    load[d] = 0;
    s[5] = -1.0f;
    return;
  }
  dir_x /= len;
  dir_z /= len;
  const float nx_pos = x + dir_x, nz_pos = z + dir_z;
  if (nx_pos < 0.0f || nz_pos < 0.0f || nx_pos >= (float)(nx - 1) || nz_pos >= (float)(ny - 1)) {
    atom_add(&counters[1], sediment);  // carried out of the map
    atom_inc(&counters[0]);
    load[d] = 0;
    s[5] = -1.0f;
    return;
  }
  float gx2, gz2;
  const float h_new = height_at(height_fixed, quantum, nx, nx_pos, nz_pos, &gx2, &gz2);
  const float dh = h_new - h_old;  // m
  const float capacity = fmax(-dh * speed * water * DROPLET_CAPACITY, DROPLET_MIN_CAPACITY);  // m of height
  const float carried = (float)sediment * quantum;
  long change = 0;
  if (dh > 0.0f || carried > capacity) {
    const float amount = dh > 0.0f ? fmin(dh, carried) : (carried - capacity) * DROPLET_DEPOSIT;
    change = max(0L, min(sediment, (long)floor(amount / quantum)));
    sediment -= change;
  } else {
    const float amount = fmin((capacity - carried) * DROPLET_ERODE, -dh);
    const long taken = max(0L, brush_quanta(nx, ny, x, z, amount, quantum, erodibility));
    sediment += taken;
    change = -taken;
  }
  speed = sqrt(fmax(0.0f, speed * speed - dh * DROPLET_GRAVITY));
  water *= 1.0f - DROPLET_EVAPORATE;
  long final_deposit = 0;
  if (step_index == DROPLET_LIFETIME - 1) {  // the end of its life: it deposits what it still carries
    final_deposit = sediment;
    sediment = 0;
    water = -1.0f;
  }
  plan_change[d] = (long2)(change, final_deposit);
  s[0] = nx_pos;
  s[1] = nz_pos;
  s[2] = dir_x;
  s[3] = dir_z;
  s[4] = speed;
  s[5] = water;
  load[d] = sediment;
}

// The changes droplet_move planned, added to the fixed heights; the droplet's state holds its new place.
__kernel void droplet_apply(volatile __global long* height_fixed, __global uint* changed, const int tiles_x,
                            const int nx, const int ny, const uint count, const __global float* state,
                            const __global float* erodibility, const __global float2* plan_place,
                            const __global long2* plan_change) {
  const uint d = get_global_id(0);
  if (d >= count) return;
  const long2 change = plan_change[d];
  if (change.x == 0 && change.y == 0) return;
  const float2 at = plan_place[d];
  if (change.x > 0) deposit_bilinear(height_fixed, changed, tiles_x, nx, at.x, at.y, change.x);
  if (change.x < 0) erode_brush(height_fixed, changed, tiles_x, nx, ny, at.x, at.y, -change.x, erodibility);
  deposit_bilinear(height_fixed, changed, tiles_x, nx, state[6 * d], state[6 * d + 1], change.y);
}
