// SPDX-License-Identifier: MIT
// Rain emitter (physics.md §4): `count` new particles written at the end of the particle arrays,
// at uniformly random (x, z) in the rain region, `spawn_height` above the terrain, or with
// `above_water` above the water's surface (the terrain plus the depth field; never below the
// contact surface, `contact_radius` above it, where the particle would be inside the ground),
// falling at `speed`. Slot k draws from the counter first_counter + k of the run's seed: the same particles
// whatever the thread count, and a resumed run draws what an uninterrupted one would.
// Regions: 0 the whole terrain, 1 a rectangle [a, b] × [c, d] (x, z), 2 a disc at (a, c) of radius b,
// 3 the whole terrain by a rain mask: the cell m with cell_cdf[m − 1] ≤ u < cell_cdf[m] (the cumulative
// share of the rain through each cell), then a uniform place in it.

#define RAIN_STREAM 0x7261696eUL  // "rain"
#define RAIN_WATER_QUANTUM 1e-6f    // m of depth a count (WATER_QUANTUM of water_depth.cl)

// The water depth at (px, pz): the fine field of water_depth.cl (counts on the vertices)
// interpolated bilinearly in the cell.
inline float water_depth_at(const __global long* water, int tnx, int tny, float tcell, float px, float pz) {
  const float u = px / tcell, v = pz / tcell;
  const int i = clamp((int)floor(u), 0, tnx - 2), j = clamp((int)floor(v), 0, tny - 2);
  const float fu = clamp(u - (float)i, 0.0f, 1.0f), fv = clamp(v - (float)j, 0.0f, 1.0f);
  const float d00 = (float)water[j * tnx + i], d10 = (float)water[j * tnx + i + 1];
  const float d01 = (float)water[(j + 1) * tnx + i], d11 = (float)water[(j + 1) * tnx + i + 1];
  const float counts = (1.0f - fv) * ((1.0f - fu) * d00 + fu * d10) + fv * ((1.0f - fu) * d01 + fu * d11);
  return RAIN_WATER_QUANTUM * counts;
}

__kernel void rain_emit(__global float* x, __global float* y, __global float* z, __global float* vx,
                        __global float* vy, __global float* vz, __global float* rho, __global int* sediment,
                        __global float* age, __global float* lifespan, __global uint* contacts, __global uint* id,
                        const uint first_index, const uint count, const ulong seed, const ulong first_counter,
                        const uint first_id, const int region, const float a, const float b, const float c,
                        const float d, const float spawn_height, const float contact_radius,
                        const float surface_eps, const float speed, const float rho0,
                        const float lifespan_mean, const float lifespan_jitter, const float spread,
                        const float gravity,
                        const __global float* terrain_height, const __global float* terrain_normal, const int tnx,
                        const int tny, const float tcell, const __global float* cell_cdf, const int cells,
                        const __global long* water, const int above_water) {
  const uint k = get_global_id(0);
  if (k >= count) return;
  const ulong counter = 4UL * (first_counter + k);
  const float u1 = rng_uniform(seed, RAIN_STREAM, counter);
  const float u2 = rng_uniform(seed, RAIN_STREAM, counter + 1);
  const float u3 = rng_uniform(seed, RAIN_STREAM, counter + 2);
  const float extent_x = (float)(tnx - 1) * tcell, extent_z = (float)(tny - 1) * tcell;
  float px, pz;
  if (region == 3) {
    int lo = 0, hi = cells - 1;
    while (lo < hi) {  // the first cell whose cumulative share exceeds u1
      const int mid = (lo + hi) >> 1;
      if (cell_cdf[mid] > u1) hi = mid; else lo = mid + 1;
    }
    const int cj = lo / (tnx - 1), ci = lo - cj * (tnx - 1);
    px = ((float)ci + u2) * tcell;
    pz = ((float)cj + rng_uniform(seed, RAIN_STREAM, counter + 3)) * tcell;
  } else if (region == 2) {  // uniform in the disc: radius ∝ sqrt(u)
    const float r = b * sqrt(u1), theta = 2.0f * M_PI_F * u2;
    px = a + r * cos(theta);
    pz = c + r * sin(theta);
  } else if (region == 1) {
    px = a + (b - a) * u1;
    pz = c + (d - c) * u2;
  } else {
    px = extent_x * u1;
    pz = extent_z * u2;
  }
  px = clamp(px, 0.0f, extent_x);
  pz = clamp(pz, 0.0f, extent_z);
  const SurfacePoint s = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, px, pz);
  const SurfacePoint contact = offset_surface(terrain_height, terrain_normal, tnx, tny, tcell, contact_radius, px, pz);
  const uint i = first_index + k;
  // Spread over the step (spread = its length; 0: every drop at its end): drop k of the step's
  // count fell since its time within the step, the k-th of count equal shares, for τ.
  const float tau = spread * ((float)(count - k) - 0.5f) / (float)count;
  x[i] = px;
  const float base = s.height + (above_water ? water_depth_at(water, tnx, tny, tcell, px, pz) : 0.0f);
  y[i] = fmax(base + spawn_height - tau * (speed + 0.5f * gravity * tau), contact.height + surface_eps);
  z[i] = pz;
  vx[i] = 0.0f;
  vy[i] = -speed - gravity * tau;
  vz[i] = 0.0f;
  rho[i] = rho0;
  sediment[i] = 0;
  age[i] = tau;
  lifespan[i] = lifespan_mean * (1.0f + lifespan_jitter * (2.0f * u3 - 1.0f));
  contacts[i] = 0;
  id[i] = first_id + k;
}
