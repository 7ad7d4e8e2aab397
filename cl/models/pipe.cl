// SPDX-License-Identifier: MIT
// Virtual-pipe shallow water with erosion (Mei, Decaudin & Hu 2007; models.md "pipe"). Terrain b and
// suspended sediment s are integer counts of the height quantum (so b + s + outflow is conserved
// exactly); water depth d (m), pipe fluxes f (m³/s, L R T B) and velocity v (m/s) are floats.
// One step of Δt, each pass reading only what the previous passes wrote:
//   pipe_flux:      d1 = d + Δt·r (read only: neighbours read d too);  f_X = max(0, f_X + Δt·A·g·Δh_X/l);  with
//                   pipe.manning_n > 0 (not in Mei 2007) the bed friction of the SPH model, implicitly,
//                   f_X /= 1 + Δt g n² v / d1^(4/3), v = f_X/(l·d1) (d1 at least 1 mm); scale all four by
//                   K = min(1, d1·l²/(Σf·Δt))   (outflow edges: outside b = d = 0; closed edges: f = 0)
//   pipe_water:     d2 = d1 + Δt(Σf_in − Σf_out)/l²;  v from the mean flux through the cell;
//                   C = min(K_c · max(sin α, sin α_min) · |v|, d2); then evaporation d = d2·e^(−K_e·Δt)
//   pipe_erode:     below capacity dissolve (1 − e^(−K_s·Δt))(C − s),
//                   above deposit (1 − e^(−K_d·Δt))(s − C) (K_s, K_d rates per second: the exact
//                   relaxation towards C over the step, whatever Δt)
//                   (the three factors of the step come from the host, in double precision)
//   pipe_send, pipe_receive, pipe_edge_outflow: sediment leaves with the water that leaves,
//                   s·f_X·Δt/(d1·l²) to each neighbour (upwind: each cell sends, then gathers what its
//                   neighbours sent it); what leaves the map is booked as outflow
// Amounts become whole quanta by stochastic rounding (counter-based random numbers of the cell under
// a key the host makes for each step and stream, rng.hpp's keyed_uniform), never by truncation: a
// step's exchange is often a few quanta, and truncating them would make the result depend on Δt.
// Fields of several components lie one plane per component on the device (GridState): flux[d·n + k]
// for the pipes L R T B, velocity[k] and velocity[n + k] for x and z.
// Compile-time constants (host -D): PIPE_*.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

// The kernels use scalars and selects rather than private arrays and branches: PoCL's vectoriser
// gives up on a work-item loop that holds a private array.

// Water level of a neighbour inside the map, d + Δt·r + b (what pipe_flux compares levels with). b is
// the terrain's float view (refreshed after every step), not the 64-bit fixed-point height: with
// 32-bit loads alone the loop over cells is vectorised 8 wide (ymm) on AVX-512, not 4.
inline float pipe_level(const __global float* height_view, const __global float* depth,
                        const __global float* rain_weight, int m, float dt, float rain_on) {
  return height_view[m] + depth[m] + dt * (PIPE_RAIN * rain_on * RAIN_WEIGHT(rain_weight, m));
}

// x^(−1/3) for x > 0 (Manning's depth term) without cbrt(), a library call that stops the vectoriser,
// and without a division: an exponent-thirds first guess (0x54a21d2a) and three Newton steps on
// 1/y³ = x, y ← y(4 − x y³)/3, reach float precision (within 2e-7 for 1e-4 ≤ x ≤ 1e4).
inline float pipe_inverse_cbrt(float x) {
  float y = as_float(0x54a21d2a - as_int(x) / 3);
  y = y * (4.0f - x * y * y * y) * (1.0f / 3.0f);  // unrolled by hand: an inner loop stops the vectoriser too
  y = y * (4.0f - x * y * y * y) * (1.0f / 3.0f);
  y = y * (4.0f - x * y * y * y) * (1.0f / 3.0f);
  return y;
}

// The new outflux through one face: the old one accelerated by the level difference (`accel` =
// Δt·A·g/l), never negative, and (with pipe.manning_n > 0) slowed implicitly by Manning's bed
// friction, f /= 1 + Δt g n² v / d^(4/3) with v = f/(l·d), which is f /= 1 + friction·f, `friction` =
// Δt g n² / (l d^(7/3)): one division per face. A pipe accelerates as a column of cross-section A,
// not of the water's own l·d, so this friction does not give Manning's discharge: a steady pipe
// carries √(A/(l d)) times it, and a sheet runs several times too fast (docs/models.md, "pipe";
// the godunov flux honours the law). Outside the map: b = d = 0, or no face at all when the edges
// are closed.
inline float pipe_face_flux(float old_flux, float level, float other_level, int inside, float accel,
                            float friction) {
#if PIPE_CLOSED
  if (!inside) return 0.0f;
#else
  other_level = inside ? other_level : 0.0f;
#endif
  const float f = fmax(0.0f, old_flux + accel * (level - other_level));
#if PIPE_FRICTION_ON
  return f / (1.0f + friction * f);
#else
  return f;
#endif
}

__kernel void pipe_flux(const __global float* height_view, const __global float* depth, __global float* flux,
                        const int nx, const int ny, const float cell, const float dt,
                        const __global float* rain_weight, const float rain_on) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const int has_l = i > 0, has_r = i < nx - 1, has_t = j > 0, has_b = j < ny - 1;
  const float d1 = depth[k] + dt * (PIPE_RAIN * rain_on * RAIN_WEIGHT(rain_weight, k));
  const float level = height_view[k] + d1;
  // Uniform over the cells, so computed once for them all.
  const float accel = dt * (PIPE_AREA * PIPE_GRAVITY) / cell;
  float friction = 0.0f;
#if PIPE_FRICTION_ON
  const float d = fmax(d1, 1e-3f), third = pipe_inverse_cbrt(d), third2 = third * third;  // d^(−1/3), d^(−2/3)
  friction = dt * PIPE_GRAVITY_N2 / cell * (third2 * third2 * third2 * third);                // d^(−7/3)
#endif
  // A neighbour outside the map reads this cell (the select in pipe_face_flux discards it).
  // Each face reads the one before through 0·f (exactly +0: the fluxes are finite and ≥ 0). Without that
  // chain the SLP vectoriser packs the four alike faces into short vectors, and a loop holding vector
  // instructions is not vectorised over the cells.
  const float level_l = pipe_level(height_view, depth, rain_weight, has_l ? k - 1 : k, dt, rain_on);
  const float f_l = pipe_face_flux(flux[0 * n + k], level, level_l, has_l, accel, friction);
  const float level_r = pipe_level(height_view, depth, rain_weight, has_r ? k + 1 : k, dt, rain_on) + 0.0f * f_l;
  const float f_r = pipe_face_flux(flux[1 * n + k], level, level_r, has_r, accel, friction);
  const float level_t = pipe_level(height_view, depth, rain_weight, has_t ? k - nx : k, dt, rain_on) + 0.0f * f_r;
  const float f_t = pipe_face_flux(flux[2 * n + k], level, level_t, has_t, accel, friction);
  const float level_b = pipe_level(height_view, depth, rain_weight, has_b ? k + nx : k, dt, rain_on) + 0.0f * f_t;
  const float f_b = pipe_face_flux(flux[3 * n + k], level, level_b, has_b, accel, friction);
  const float total = f_l + f_r + f_t + f_b;
  const float scale = total > 0.0f ? fmin(1.0f, d1 * cell * cell / (total * dt)) : 0.0f;
  flux[0 * n + k] = f_l * scale;
  flux[1 * n + k] = f_r * scale;
  flux[2 * n + k] = f_t * scale;
  flux[3 * n + k] = f_b * scale;
}

// The transport capacity C = K_c · max(sin α, sin α_min) · |v| (m), at most the water's own depth d
// (thin films move fast). pipe_water computes it while the cell's new velocity is in registers and
// the loop runs wide on 32-bit values; pipe_erode, whose 64-bit heights and loads keep it 4 wide, reads it.
// The slope comes from the heights as the step began (the view pipe_erode does not write).
// Central differences, one-sided at the edges. x and z are written differently on purpose, and the
// sums of squares as fma: isomorphic x/z pairs are what the SLP vectoriser packs into 2-wide vectors
// first, and a work-item holding such vectors is not vectorised across cells.
inline float pipe_capacity(const __global float* height_view, int nx, int ny, int i, int j, int k, float cell,
                           float vx, float vz, float depth) {
  const int has_l = i > 0, has_r = i < nx - 1, up = j > 0 ? nx : 0, down = j < ny - 1 ? nx : 0;
  const float gx = (height_view[k + has_r] - height_view[k - has_l]) / ((float)(has_l + has_r) * cell);
  const float gz = (height_view[k + down] - height_view[k - up]) * ((up && down ? 0.5f : 1.0f) / cell);
  const float slope2 = fma(gx, gx, gz * gz);
  const float sin_slope = sqrt(slope2 / (1.0f + slope2));
  const float speed = sqrt(fma(vx, vx, vz * vz));  // not hypot: no overflow to guard against, and it is slow on CPUs
  return fmin(PIPE_CAPACITY * fmax(sin_slope, PIPE_MIN_TILT) * speed, depth);
}

// The speed the next step's CFL limit counts (pipe_stats) is written here too, where the velocity
// and the fluxes are in registers: pipe_stats then reads two planes instead of eight.
__kernel void pipe_water(__global float* depth, const __global float* flux, __global float* velocity,
                         __global float* previous_depth, const __global float* height_view, __global float* capacity,
                         const int nx, const int ny, const float cell, const float dt,
                         const __global float* rain_weight, const float rain_on, const float evaporation_factor,
                         __global float* cfl_speed2) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  // What the neighbours send towards this cell (their pipe d ^ 1); nothing from outside the map.
  const float in_l = i > 0 ? flux[1 * n + k - 1] : 0.0f, in_r = i < nx - 1 ? flux[0 * n + k + 1] : 0.0f;
  const float in_t = j > 0 ? flux[3 * n + k - nx] : 0.0f, in_b = j < ny - 1 ? flux[2 * n + k + nx] : 0.0f;
  const float out_l = flux[0 * n + k], out_r = flux[1 * n + k], out_t = flux[2 * n + k], out_b = flux[3 * n + k];
  const float out_total = out_l + out_r + out_t + out_b, in_total = in_l + in_r + in_t + in_b;
  const float d1 = depth[k] + dt * (PIPE_RAIN * rain_on * RAIN_WEIGHT(rain_weight, k));  // the same d1 the flux pass used
  const float d2 = fmax(0.0f, d1 + dt * (in_total - out_total) / (cell * cell));
  previous_depth[k] = d1;
  const float d_evaporated = d2 * evaporation_factor;
  depth[k] = d_evaporated;
  // Mean flux through the cell in x (from the left in, out to the right, ...) over the mean depth.
  // x and z are written differently on purpose (see pipe_erode): isomorphic pairs get packed by the
  // SLP vectoriser, and then the loop over cells is not vectorised.
  const float wx = 0.5f * (in_l - out_l + out_r - in_r);
  const float wz = ((in_t + out_b) - (out_t + in_b)) * 0.5f;
  const float mean_depth = 0.5f * (d1 + d2);
  const float per_area = mean_depth > 1e-6f ? 1.0f / (cell * mean_depth) : 0.0f;
  const float vx = wx * per_area, vz = per_area * wz;
  velocity[k] = vx;
  velocity[n + k] = vz;
  capacity[k] = pipe_capacity(height_view, nx, ny, i, j, k, cell, vx, vz, d2);
  // The CFL limit counts a speed only where the water is at least PIPE_CFL_DEPTH deep and the flux
  // limit K did not act (the cell kept some of its water): a limited cell's 'velocity' is its whole
  // volume leaving in one step, about l/Δt whatever Δt, so counting it shrinks the step by the CFL
  // factor every step; the limit itself keeps such cells non-negative, and the wave speed sqrt(g·d)
  // still bounds the step.
  const int limited = out_total * dt >= 0.999f * d1 * cell * cell;
  const float v2 = vx * vx + vz * vz;
  cfl_speed2[k] = d_evaporated >= PIPE_CFL_DEPTH && !limited ? v2 : 0.0f * v2;  // NaN stays NaN
}

__kernel void pipe_erode(__global long* height, __global long* sediment,
                         const __global float* capacity_of_cell, const int nx, const int ny, const float quantum,
                         const float dissolved_fraction, const float deposited_fraction, const ulong key,
                         const __global float* rock_erodibility, const __global float* sediment_erodibility,
                         const __global long* ground_sediment, __global int* sendable) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const float capacity = capacity_of_cell[k];  // m, from pipe_water
  const long load = sediment[k];
  const float s = (float)load * quantum;
  const float u = keyed_uniform(key, (uint)k);  // the step's key for the erosion stream (host)
  // Below capacity dissolve, above it deposit (never more than the load); both amounts are ≥ 0, so
  // truncation is the floor. Positive: from the bed into the water.
  // With a layer stack the dissolution is the bed's detachment (docs/layers.md); never the deposition.
  // Divided by the quantum, not multiplied by its reciprocal: a product here would be fused with
  // the + u into one multiply-add without a layered ground but not with one (the demand passes
  // through bed_detachment), and a ground of erodibility 1 must change nothing, bit for bit.
  const long dissolved = (long)(BED_DETACHMENT(dissolved_fraction * fmax(capacity - s, 0.0f) / quantum, k) + u);
  const long deposited = min(load, (long)(deposited_fraction * fmax(s - capacity, 0.0f) / quantum + u));
  const long exchanged = capacity > s ? dissolved : -deposited;
  height[k] -= exchanged;
  sediment[k] = load + exchanged;
  sendable[k] = (int)min(load + exchanged, PIPE_SENDABLE);
}

// pipe_send: the sediment each cell sends through its four pipes: their outflows' shares of the
// water it had, f·share (together at most 1), split by systematic sampling with one random u per
// cell and step, so each pipe carries s·f·share in expectation and all four together never more
// than s. Stored one plane per direction (L R T B: sent[d·n + k]); pipe_receive then moves them, and
// pipe_edge_outflow books what left the map. 32-bit loads, stores and random numbers only, so the
// loop runs 8 or 16 cells wide, not 4: s is pipe_erode's copy of the load capped at PIPE_SENDABLE
// quanta (host -D, 2^30: kPipeSendable, over a kilometre of sediment in a cell at the default
// quantum); a cell holding more sends shares of that and keeps the rest for later steps.
__kernel void pipe_send(const __global int* sendable, const __global float* flux, const __global float* previous_depth,
                        __global int* sent, const int nx, const int ny, const float cell, const float dt,
                        const ulong key) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  // share = Δt / (d1·l²): the fraction of the cell's water one unit of flux carries away in a step.
  const float volume = previous_depth[k] * cell * cell;
  const float share = volume > 0.0f ? dt / volume : 0.0f;
  const float u = keyed_uniform(key, (uint)k);  // the step's key for the transport stream (host)
  const float s = (float)sendable[k];
  // Cumulative shares up to and including pipe d, capped at the whole load; the pipe sends the
  // difference of the sampled amounts at its two ends. Every amount is ≥ 0, so truncation is the floor.
  const float c1 = flux[0 * n + k] * share, c2 = c1 + flux[1 * n + k] * share;
  const float c3 = c2 + flux[2 * n + k] * share, c4 = c3 + flux[3 * n + k] * share;
  // At most s·(1 + 2^-23) + 1 < 2^31.
  const int at0 = (int)u, at1 = (int)(s * fmin(1.0f, c1) + u), at2 = (int)(s * fmin(1.0f, c2) + u);
  const int at3 = (int)(s * fmin(1.0f, c3) + u), at4 = (int)(s * fmin(1.0f, c4) + u);
  sent[0 * n + k] = at1 - at0;
  sent[1 * n + k] = at2 - at1;
  sent[2 * n + k] = at3 - at2;
  sent[3 * n + k] = at4 - at3;
}

__kernel void pipe_receive(const __global long* sediment, __global long* sediment_next, const __global int* sent,
                           const int nx, const int ny) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  // The neighbours' sediment towards this cell comes through their pipe d ^ 1; nothing from outside.
  const long in = (long)(i > 0 ? sent[1 * n + k - 1] : 0) + (long)(i < nx - 1 ? sent[0 * n + k + 1] : 0) +
                  (long)(j > 0 ? sent[3 * n + k - nx] : 0) + (long)(j < ny - 1 ? sent[2 * n + k + nx] : 0);
  const long out = (long)sent[0 * n + k] + (long)sent[1 * n + k] + (long)sent[2 * n + k] + (long)sent[3 * n + k];
  sediment_next[k] = sediment[k] - out + in;
}

// What the border cells sent out of the map, one work-item per border face: left and right columns,
// then top and bottom rows. An integer sum, so the order of the atomics does not matter.
__kernel void pipe_edge_outflow(const __global int* sent, const int nx, const int ny,
                                volatile __global long* outflow) {
  const int f = get_global_id(0), n = nx * ny;
  if (f >= 2 * (nx + ny)) return;
  long out;
  if (f < 2 * ny) {
    const int j = f >> 1, right = f & 1;
    out = sent[right * n + j * nx + (right ? nx - 1 : 0)];
  } else {
    const int i = (f - 2 * ny) >> 1, bottom = f & 1;
    out = sent[(2 + bottom) * n + (bottom ? ny - 1 : 0) * nx + i];
  }
  if (out > 0) atom_add(outflow, out);
}

// The water that left the map through each edge face this step, added to that face's running total
// (edge_water, in counts of `water_quantum` m³, one per face in pipe_edge_outflow's order: the rows'
// west and east faces, then the columns' north and south faces). Each face owns its total, so the
// sum needs no atomics and is the same whatever the device; rounding to the nearest count is
// unbiased to half a count a face and step (a count is 10⁻⁹ m of depth over a cell).
__kernel void pipe_edge_water(const __global float* flux, const int nx, const int ny, const float dt,
                              const float water_quantum, __global long* edge_water) {
  const int f = get_global_id(0), n = nx * ny;
  if (f >= 2 * (nx + ny)) return;
  float out;
  if (f < 2 * ny) {
    const int j = f >> 1, right = f & 1;
    out = flux[right * n + j * nx + (right ? nx - 1 : 0)];
  } else {
    const int i = (f - 2 * ny) >> 1, bottom = f & 1;
    out = flux[(2 + bottom) * n + (bottom ? ny - 1 : 0) * nx + i];
  }
  edge_water[f] += (long)(out * dt / water_quantum + 0.5f);
}

// The option pipe.transport = "semi-lagrangian" (Mei 2007's advection) instead of pipe_transport:
// s_new(x) = s(x − v·Δt), bilinear, clamped to the map. It does not conserve mass; what it loses
// (or gains) is the exact sum of s_old − s_new, booked in `lost`.
__kernel void pipe_advect(const __global long* sediment, __global long* sediment_next, const __global float* velocity,
                          const int nx, const int ny, const float cell, const float dt, volatile __global long* lost) {
  const int k = get_global_id(0), n = nx * ny;
  if (k >= n) return;
  const int j = grid_row(k, nx), i = k - j * nx;
  const float x = clamp((float)i - velocity[k] * dt / cell, 0.0f, (float)(nx - 1));
  const float z = clamp((float)j - velocity[n + k] * dt / cell, 0.0f, (float)(ny - 1));
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

// Largest depth and counted speed (pipe_water's cfl_speed2) per block of cells, for the adaptive
// time step, and the sums that give the flow's Froude number: the mean of the counted cells'
// Froude numbers weighted by their discharge per width, inside the map (a map edge's cell is a
// brink, where the water leaves at critical depth whatever the flux). The local-inertial flux's
// equations hold a sheet only below Froude 3/5 (docs/models.md); weighting by discharge counts the
// sheet and the channels, not a wetting front's thin tip.
__kernel void pipe_stats(const __global float* depth, const __global float* cfl_speed2, const int nx, const int ny,
                         const int chunk, __global float* stats) {
  const int b = get_global_id(0), n = nx * ny;
  // Maxima of the bits: a non-negative float orders as its bits do, and NaN's bits lie above
  // infinity's, so a NaN reaches the host (which stops the run) without a test per cell; the sign
  // bit is cleared (a −0 would otherwise be the largest). An integer max is a reduction the loop
  // vectoriser knows; fmax with NaN selects is not.
  uint dmax = 0u, vmax2 = 0u;
  float discharge = 0.0f, discharge_froude = 0.0f;
  for (int k = b * chunk; k < min(n, (b + 1) * chunk); ++k) {
    const float d = depth[k], v2 = cfl_speed2[k];
    dmax = max(dmax, as_uint(d) & 0x7fffffffu);
    vmax2 = max(vmax2, as_uint(v2) & 0x7fffffffu);
    const int j = grid_row(k, nx), i = k - j * nx;
    if (i > 0 && i < nx - 1 && j > 0 && j < ny - 1 && v2 > 0.0f) {
      const float speed = sqrt(v2), q = speed * d;
      discharge += q;
      discharge_froude += q * speed / sqrt(PIPE_GRAVITY * d);
    }
  }
  stats[4 * b] = as_float(dmax);
  stats[4 * b + 1] = sqrt(as_float(vmax2));
  stats[4 * b + 2] = discharge;
  stats[4 * b + 3] = discharge_froude;
}
