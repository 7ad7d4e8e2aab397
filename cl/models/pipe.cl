// SPDX-License-Identifier: MIT
// Virtual-pipe shallow water with erosion (Mei, Decaudin & Hu 2007; models.md "pipe"). Terrain b and
// suspended sediment s are integer counts of the height quantum (so b + s + outflow is conserved
// exactly); water depth d (m), pipe fluxes f (m³/s, L R T B) and velocity v (m/s) are floats.
// One step of Δt, each pass reading only what the previous passes wrote:
//   pipe_flux:      d1 = d + Δt·r (read only: neighbours read d too);  f_X = max(0, f_X + Δt·A·g·Δh_X/l);  with
//                   pipe.manning_n > 0 (not in Mei 2007) the bed friction of the SPH model, implicitly,
//                   f_X /= 1 + Δt g n² v / d1^(4/3), v = f_X/(l·d1); scale all four by
//                   K = min(1, d1·l²/(Σf·Δt))   (outflow edges: outside b = d = 0; closed edges: f = 0)
//   pipe_water:     d2 = d1 + Δt(Σf_in − Σf_out)/l²;  v from the mean flux through the cell
//   pipe_erode:     C = K_c · max(sin α, sin α_min) · |v|; below capacity dissolve (1 − e^(−K_s·Δt))(C − s),
//                   above deposit (1 − e^(−K_d·Δt))(s − C) (K_s, K_d rates per second: the exact
//                   relaxation towards C over the step, whatever Δt); then evaporation d *= e^(−K_e·Δt)
//   pipe_transport: sediment leaves with the water that leaves, s·f_X·Δt/(d1·l²) to each neighbour
//                   (upwind, a gather: each cell adds what its neighbours send it); what leaves the map
//                   is booked as outflow
// Amounts become whole quanta by stochastic rounding (counter-based random numbers of the cell and
// the step), never by truncation: a step's exchange is often a few quanta, and truncating them would
// make the result depend on Δt.
// Compile-time constants (host -D): PIPE_*.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

__constant int2 kPipeNeighbour[4] = {(int2)(-1, 0), (int2)(1, 0), (int2)(0, -1), (int2)(0, 1)};  // L R T B

inline int pipe_inside(int x, int z, int nx, int ny) { return x >= 0 && z >= 0 && x < nx && z < ny; }

__kernel void pipe_flux(const __global long* height, const __global float* depth, __global float* flux, const int nx,
                        const int ny, const float quantum, const float cell, const float dt) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int2 ij = grid_coords(k, nx);
  const int i = ij.x, j = ij.y;
  const float d1 = depth[k] + dt * PIPE_RAIN;
  const float level = (float)height[k] * quantum + d1;
  float f[4], total = 0.0f;
  for (int d = 0; d < 4; ++d) {
    const int x = i + kPipeNeighbour[d].x, z = j + kPipeNeighbour[d].y;
    float other;
    if (pipe_inside(x, z, nx, ny)) {
      const int m = z * nx + x;
      other = (float)height[m] * quantum + depth[m] + dt * PIPE_RAIN;
    } else {
#if PIPE_CLOSED
      f[d] = 0.0f;
      continue;
#else
      other = 0.0f;  // outside: b = 0, d = 0
#endif
    }
    f[d] = fmax(0.0f, flux[4 * k + d] + dt * PIPE_AREA * PIPE_GRAVITY * (level - other) / cell);
#if PIPE_FRICTION_ON
    // Manning's bed friction on the flow through the face (implicit: it only slows the flow).
    const float h = fmax(d1, 1e-3f), v = f[d] / (cell * h);
    f[d] /= 1.0f + dt * PIPE_GRAVITY_N2 * v / (h * cbrt(h));
#endif
    total += f[d];
  }
  const float scale = total > 0.0f ? fmin(1.0f, d1 * cell * cell / (total * dt)) : 0.0f;
  for (int d = 0; d < 4; ++d) flux[4 * k + d] = f[d] * scale;
}

__kernel void pipe_water(__global float* depth, const __global float* flux, __global float* velocity,
                         __global float* previous_depth, const int nx, const int ny, const float cell, const float dt) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int2 ij = grid_coords(k, nx);
  const int i = ij.x, j = ij.y;
  float in[4] = {0.0f, 0.0f, 0.0f, 0.0f}, out_total = 0.0f, in_total = 0.0f;
  for (int d = 0; d < 4; ++d) {
    out_total += flux[4 * k + d];
    const int x = i + kPipeNeighbour[d].x, z = j + kPipeNeighbour[d].y;
    if (!pipe_inside(x, z, nx, ny)) continue;
    in[d] = flux[4 * (z * nx + x) + (d ^ 1)];
    in_total += in[d];
  }
  const float d1 = depth[k] + dt * PIPE_RAIN;  // the same d1 the flux pass used
  const float d2 = fmax(0.0f, d1 + dt * (in_total - out_total) / (cell * cell));
  previous_depth[k] = d1;
  depth[k] = d2;
  // Mean flux through the cell in x (from the left in, out to the right, ...) over the mean depth.
  const float wx = 0.5f * (in[0] - flux[4 * k + 0] + flux[4 * k + 1] - in[1]);
  const float wz = 0.5f * (in[2] - flux[4 * k + 2] + flux[4 * k + 3] - in[3]);
  const float mean_depth = 0.5f * (d1 + d2);
  velocity[2 * k] = mean_depth > 1e-6f ? wx / (cell * mean_depth) : 0.0f;
  velocity[2 * k + 1] = mean_depth > 1e-6f ? wz / (cell * mean_depth) : 0.0f;
}

#define PIPE_ERODE_STREAM 0x70657264UL      // "perd"
#define PIPE_TRANSPORT_STREAM 0x70747273UL  // "ptrs"

// Uniform in [0, 1): one number per cell and step of a stream.
inline float pipe_random(ulong seed, ulong stream, ulong step, int cells, int k) {
  return rng_uniform(seed, stream, step * (ulong)cells + (ulong)k);
}

__kernel void pipe_erode(__global long* height, const __global float* height_view, __global long* sediment,
                         __global float* depth, const __global float* velocity, const int nx, const int ny,
                         const float quantum, const float cell, const float dt, const ulong seed,
                         const ulong step_index) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int2 ij = grid_coords(k, nx);
  const int i = ij.x, j = ij.y;
  // The slope from the heights as the step began (height_view), not from height, which this kernel
  // changes: no cell reads what another work-item writes.
  const int i0 = max(i - 1, 0), i1 = min(i + 1, nx - 1), j0 = max(j - 1, 0), j1 = min(j + 1, ny - 1);
  const float gx = (height_view[j * nx + i1] - height_view[j * nx + i0]) / ((float)(i1 - i0) * cell);
  const float gz = (height_view[j1 * nx + i] - height_view[j0 * nx + i]) / ((float)(j1 - j0) * cell);
  const float sin_slope = sqrt(gx * gx + gz * gz) / sqrt(1.0f + gx * gx + gz * gz);
  const float vx = velocity[2 * k], vz = velocity[2 * k + 1];
  const float speed = sqrt(vx * vx + vz * vz);  // not hypot: no overflow to guard against, and it is slow on CPUs
  // The water cannot carry more sediment than its own depth (thin films move fast).
  const float capacity = fmin(PIPE_CAPACITY * fmax(sin_slope, PIPE_MIN_TILT) * speed, depth[k]);  // m
  const float s = (float)sediment[k] * quantum;
  const float u = pipe_random(seed, PIPE_ERODE_STREAM, step_index, nx * ny, k);
  if (capacity > s) {
    const long q = (long)floor(-expm1(-PIPE_DISSOLVE * dt) * (capacity - s) / quantum + u);
    height[k] -= q;
    sediment[k] += q;
  } else {
    const long q = min(sediment[k], (long)floor(-expm1(-PIPE_DEPOSIT * dt) * (s - capacity) / quantum + u));
    height[k] += q;
    sediment[k] -= q;
  }
  depth[k] *= exp(-PIPE_EVAPORATION * dt);
}

// The sediment a cell sends through pipe d: its outflows' shares of the water it had, f·share
// (together at most 1), split by systematic sampling with one random u per cell and step, so each
// pipe carries s·f·share in expectation and all four together never more than s. Sender and
// receiver evaluate this same function on the same values, so what leaves one cell arrives in the
// other to the quantum.
inline long pipe_sent(long sediment, const __global float* flux4, float share, float u, int d) {
  float before = 0.0f;
  for (int e = 0; e < d; ++e) before += flux4[e] * share;
  const float upto = fmin(1.0f, before + flux4[d] * share);
  before = fmin(1.0f, before);
  return (long)floor((float)sediment * upto + u) - (long)floor((float)sediment * before + u);
}

__kernel void pipe_transport(const __global long* sediment, __global long* sediment_next, const __global float* flux,
                             const __global float* previous_depth, const int nx, const int ny, const float cell,
                             const float dt, const ulong seed, const ulong step_index, volatile __global long* outflow) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int2 ij = grid_coords(k, nx);
  const int i = ij.x, j = ij.y;
  const float cell2 = cell * cell;
  // share = Δt / (d1·l²): the fraction of the cell's water one unit of flux carries away in a step.
  const float volume = previous_depth[k] * cell2;
  const float share = volume > 0.0f ? dt / volume : 0.0f;
  const float u = pipe_random(seed, PIPE_TRANSPORT_STREAM, step_index, nx * ny, k);
  long s = sediment[k];
  for (int d = 0; d < 4; ++d) {
    const long sent = pipe_sent(sediment[k], flux + 4 * k, share, u, d);
    s -= sent;
    const int x = i + kPipeNeighbour[d].x, z = j + kPipeNeighbour[d].y;
    if (!pipe_inside(x, z, nx, ny)) {
      if (sent > 0) atom_add(outflow, sent);
      continue;
    }
    const int m = z * nx + x;
    const float volume_m = previous_depth[m] * cell2;
    const float share_m = volume_m > 0.0f ? dt / volume_m : 0.0f;
    s += pipe_sent(sediment[m], flux + 4 * m, share_m, pipe_random(seed, PIPE_TRANSPORT_STREAM, step_index, nx * ny, m),
                   d ^ 1);
  }
  sediment_next[k] = s;
}

// The option pipe.transport = "semi-lagrangian" (Mei 2007's advection) instead of pipe_transport:
// s_new(x) = s(x − v·Δt), bilinear, clamped to the map. It does not conserve mass; what it loses
// (or gains) is the exact sum of s_old − s_new, booked in `lost`.
__kernel void pipe_advect(const __global long* sediment, __global long* sediment_next, const __global float* velocity,
                          const int nx, const int ny, const float cell, const float dt, volatile __global long* lost) {
  const int k = get_global_id(0);
  if (k >= nx * ny) return;
  const int2 ij = grid_coords(k, nx);
  const int i = ij.x, j = ij.y;
  const float x = clamp((float)i - velocity[2 * k] * dt / cell, 0.0f, (float)(nx - 1));
  const float z = clamp((float)j - velocity[2 * k + 1] * dt / cell, 0.0f, (float)(ny - 1));
  const int i0 = min((int)x, nx - 2), j0 = min((int)z, ny - 2);
  const float u = x - (float)i0, v = z - (float)j0;
  const int m = j0 * nx + i0;
  const float s = (1.0f - u) * (1.0f - v) * (float)sediment[m] + u * (1.0f - v) * (float)sediment[m + 1] +
                  (1.0f - u) * v * (float)sediment[m + nx] + u * v * (float)sediment[m + nx + 1];
  const long next = (long)floor(s);
  sediment_next[k] = next;
  const long change = sediment[k] - next;
  if (change != 0) atom_add(lost, change);
}

// Largest depth and speed per block of cells, for the adaptive time step. A speed counts only
// where the water is at least PIPE_CFL_DEPTH deep and the flux limit K did not act (the cell kept
// some of its water): a limited cell's 'velocity' is its whole volume leaving in one step, about
// l/Δt whatever Δt, so counting it shrinks the step by the CFL factor every step; the limit itself
// keeps such cells non-negative, and the wave speed sqrt(g·d) still bounds the step.
__kernel void pipe_stats(const __global float* depth, const __global float* velocity, const __global float* flux,
                         const __global float* previous_depth, const int n, const int chunk, const float cell,
                         const float dt, __global float* stats) {
  const int b = get_global_id(0);
  float dmax = 0.0f, vmax2 = 0.0f;
  for (int k = b * chunk; k < min(n, (b + 1) * chunk); ++k) {
    const float vx = velocity[2 * k], vz = velocity[2 * k + 1];
    const float out = (flux[4 * k] + flux[4 * k + 1] + flux[4 * k + 2] + flux[4 * k + 3]) * dt;
    const int limited = out >= 0.999f * previous_depth[k] * cell * cell;
    const float v2 = depth[k] >= PIPE_CFL_DEPTH && !limited ? vx * vx + vz * vz : 0.0f;
    // fmax ignores NaN: turn it into infinity so that the host sees it.
    dmax = fmax(dmax, isnan(depth[k]) ? INFINITY : depth[k]);
    vmax2 = fmax(vmax2, isnan(vx + vz) ? INFINITY : v2);
  }
  stats[2 * b] = dmax;
  stats[2 * b + 1] = sqrt(vmax2);
}
