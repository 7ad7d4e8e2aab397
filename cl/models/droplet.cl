// SPDX-License-Identifier: MIT
// Particle droplets (Beyer 2015; models.md "droplet"). A batch of droplets moves in lockstep: one
// launch moves every droplet of the batch one cell over the terrain as the previous step left it
// (height, m, the float view), and the host refreshes that view before the next. Changes go
// straight into the fixed-point heights (counts of the height quantum), which no droplet reads,
// with 64-bit integer atomics, so a step's result does not depend on the order of the droplets.
// Sediment is carried as quanta too: what a droplet erodes, it deposits (or carries out of the
// map, booked as outflow) exactly.
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

inline float height_at(const __global float* h, int nx, float x, float z, float* gx, float* gz) {
  const int i = (int)x, j = (int)z;
  const float u = x - (float)i, v = z - (float)j;
  const int k = j * nx + i;
  const float h00 = h[k], h10 = h[k + 1], h01 = h[k + nx], h11 = h[k + nx + 1];
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

// Erodes floor(amount·ē/quantum) quanta from the vertices within DROPLET_RADIUS cells, weighted by
// (radius − distance)·e, with e the vertex's erodibility (1 without a layer stack) and ē its mean
// under the brush: a layered bed gives in proportion to how easily it erodes, a frozen vertex
// nothing (docs/layers.md). Returns the quanta taken.
#define BRUSH_SIDE (2 * (int)DROPLET_RADIUS_CELLS + 2)
inline long erode_brush(volatile __global long* height_fixed, __global uint* changed, int tiles_x, int nx, int ny,
                        float x, float z, float amount, float quantum, const __global float* erodibility) {
  const int r = DROPLET_RADIUS_CELLS;
  const int ci = (int)x, cj = (int)z;
  // Only rows and columns of the map nearer than the radius can hold a weight: every vertex of
  // another lies at least the radius away, its weight is 0, and adding 0 to the sums changes no bit.
  // (A radius of 3 cells leaves 6 × 6 of the 8 × 8 vertices around the droplet's cell.)
  int i0 = r + 1, i1 = -r - 1, j0 = r + 1, j1 = -r - 1;
  for (int d = -r; d <= r + 1; ++d) {
    const float dx = (float)(ci + d) - x, dz = (float)(cj + d) - z;
    if (ci + d >= 0 && ci + d < nx && sqrt(dx * dx) < DROPLET_RADIUS) {
      i0 = min(i0, d);
      i1 = max(i1, d);
    }
    if (cj + d >= 0 && cj + d < ny && sqrt(dz * dz) < DROPLET_RADIUS) {
      j0 = min(j0, d);
      j1 = max(j1, d);
    }
  }
  // The weights once, kept for the second pass.
  float weight[BRUSH_SIDE * BRUSH_SIDE];
  float total = 0.0f, plain_total = 0.0f;
  for (int dj = j0; dj <= j1; ++dj) {
    for (int di = i0; di <= i1; ++di) {
      const int a = ci + di, b = cj + dj;
      const float dx = (float)a - x, dz = (float)b - z;  // sqrt, not hypot: far faster on CPUs
      const float w = fmax(0.0f, DROPLET_RADIUS - sqrt(dx * dx + dz * dz));
      const float e = ERODIBILITY(erodibility, b * nx + a);
      weight[(dj + r) * BRUSH_SIDE + (di + r)] = w * e;
      total += w * e;
      plain_total += w;
    }
  }
  const long quanta = plain_total > 0.0f ? (long)floor(amount * (total / plain_total) / quantum) : 0;
  if (quanta <= 0 || total <= 0.0f) return 0;
  mark_changed_tiles(changed, tiles_x, ci + i0, ci + i1, cj + j0, cj + j1);
  long taken = 0, best_part = -1;
  int best = -1;
  for (int dj = j0; dj <= j1; ++dj) {
    for (int di = i0; di <= i1; ++di) {
      const float share = weight[(dj + r) * BRUSH_SIDE + (di + r)];
      if (share <= 0.0f) continue;  // outside the disc, or a frozen vertex: w below would be 0
      const float w = share / total;
      if (w <= 0.0f) continue;
      const int m = (cj + dj) * nx + (ci + di);
      const long part = min((long)floor((float)quanta * w), quanta - taken);
      taken += part;
      if (part > best_part) {
        best_part = part;
        best = m;
      }
      if (part > 0) atom_add(&height_fixed[m], -part);
    }
  }
  if (quanta - taken > 0 && best >= 0) atom_add(&height_fixed[best], -(quanta - taken));
  return quanta;
}

// Droplet state between steps: (x, z, dir_x, dir_z, speed, water) in cell units; water < 0 marks
// a droplet that has finished. droplet_spawn places a batch's droplets; the host then stores them
// in the order of where they fell (row by row), and droplet_step moves droplet g with work-item g:
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

// One step of every droplet of the batch.
__kernel void droplet_step(const __global float* height, volatile __global long* height_fixed, __global uint* changed,
                           const int tiles_x, const int nx, const int ny, const float quantum, const uint count,
                           const int step_index, __global float* state,
                           __global long* load, volatile __global long* counters,
                           const __global float* erodibility) {
  const uint d = get_global_id(0);
  if (d >= count) return;
  __global float* s = state + 6 * d;
  if (s[5] < 0.0f) return;
  float x = s[0], z = s[1], speed = s[4], water = s[5];
  long sediment = load[d];  // quanta of height
  float gx, gz;
  const float h_old = height_at(height, nx, x, z, &gx, &gz);
  float dir_x = s[2] * DROPLET_INERTIA - gx * (1.0f - DROPLET_INERTIA);
  float dir_z = s[3] * DROPLET_INERTIA - gz * (1.0f - DROPLET_INERTIA);
  const float len = sqrt(dir_x * dir_x + dir_z * dir_z);
  if (len == 0.0f) {  // flat: the droplet stops and deposits what it carries
    deposit_bilinear(height_fixed, changed, tiles_x, nx, x, z, sediment);
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
  const float h_new = height_at(height, nx, nx_pos, nz_pos, &gx2, &gz2);
  const float dh = h_new - h_old;  // m
  const float capacity = fmax(-dh * speed * water * DROPLET_CAPACITY, DROPLET_MIN_CAPACITY);  // m of height
  const float carried = (float)sediment * quantum;
  if (dh > 0.0f || carried > capacity) {
    const float amount = dh > 0.0f ? fmin(dh, carried) : (carried - capacity) * DROPLET_DEPOSIT;
    const long q = min(sediment, (long)floor(amount / quantum));
    deposit_bilinear(height_fixed, changed, tiles_x, nx, x, z, q);
    sediment -= q;
  } else {
    const float amount = fmin((capacity - carried) * DROPLET_ERODE, -dh);
    sediment += erode_brush(height_fixed, changed, tiles_x, nx, ny, x, z, amount, quantum, erodibility);
  }
  speed = sqrt(fmax(0.0f, speed * speed - dh * DROPLET_GRAVITY));
  water *= 1.0f - DROPLET_EVAPORATE;
  if (step_index == DROPLET_LIFETIME - 1) {  // the end of its life: it deposits what it still carries
    deposit_bilinear(height_fixed, changed, tiles_x, nx, nx_pos, nz_pos, sediment);
    sediment = 0;
    water = -1.0f;
  }
  s[0] = nx_pos;
  s[1] = nz_pos;
  s[2] = dir_x;
  s[3] = dir_z;
  s[4] = speed;
  s[5] = water;
  load[d] = sediment;
}
