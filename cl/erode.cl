// SPDX-License-Identifier: MIT
// Erosion, deposition and evaporation (physics.md §4), per particle after the drift. Sediment and
// terrain changes are integer counts of the volume quantum Q = q·cell² (q the height quantum), so
// every exchange moves exactly what the particle gains or loses:
//   footprint: the amount is split over the tile's 4 vertices with bilinear weights w_k (Σ = 1),
//              floor(amount·w_k) each, the remainder to the vertex of largest weight;
//   capacity model (EROSION_MODEL 0), for a particle within contact distance of the terrain:
//     C = K_c V |v_t| max(sin α, sin α_min) · (d/dx)^β;  s < C: erode min(K_s (C − s) dt_e, limit)
//                                                        s ≥ C: deposit K_d (s − C) dt_e
//     d/dx, the local flow depth in particle layers, from the SPH neighbour count; β =
//     erosion.depth_exponent (0 gives physics.md's C; 1 makes capacity follow unit discharge d·|v|,
//     as stream power does, so concentrated flow incises channels)
//   acidity model (EROSION_MODEL 1, Fritz 2016): each contact erodes `acidity`·cell² until the
//     particle has eroded `capacity_contacts` times;
//   evaporation: at the end of its lifespan a particle deposits its sediment (deposit_fraction of
//     it; the rest is booked as lost) and is removed.
// limit = limit_fraction · cell² · (highest − lowest corner of the tile): no single event digs a
// pit deeper than the local relief. Heights change only when terrain_apply adds the deltas.
// Compile-time constants (host -D): EROSION_*; dt_e = dt · time_scale is an argument.

// Adds ±quanta to the tile's 4 vertices in proportion to the bilinear weights, exactly.
inline void spread_quanta(volatile __global long* delta, int k00, int nx, float fx, float fz, long quanta,
                          long sign) {
  if (quanta == 0) return;
  const float w[4] = {(1.0f - fx) * (1.0f - fz), fx * (1.0f - fz), (1.0f - fx) * fz, fx * fz};
  const int k[4] = {k00, k00 + 1, k00 + nx, k00 + nx + 1};
  long part[4];
  long given = 0;
  int largest = 0;
  for (int c = 0; c < 4; ++c) {
    part[c] = (long)floor((float)quanta * w[c]);
    part[c] = min(part[c], quanta - given);
    given += part[c];
    if (w[c] > w[largest]) largest = c;
  }
  part[largest] += quanta - given;
  for (int c = 0; c < 4; ++c) {
    if (part[c] != 0) atom_add(&delta[k[c]], sign * part[c]);
  }
}

__kernel void erode_exchange(const __global float* x, const __global float* y, const __global float* z,
                             const __global float* vx, const __global float* vy, const __global float* vz,
                             __global int* sediment, __global uint* contacts, const __global float* age,
                             const __global float* lifespan, __global uint* id, const __global float* neighbours,
                             const uint n, const float dt_e,
                             const __global float* terrain_height, const __global float* terrain_normal,
                             const int tnx, const int tny, const float tcell, volatile __global long* delta,
                             volatile __global long* counters) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  if (id[i] & DEAD_FLAG) return;
  // The tile under the particle and its bilinear weights.
  const float u = clamp(x[i] / tcell, 0.0f, (float)(tnx - 1));
  const float v = clamp(z[i] / tcell, 0.0f, (float)(tny - 1));
  const int ti = min((int)u, tnx - 2), tj = min((int)v, tny - 2);
  const float fx = u - (float)ti, fz = v - (float)tj;
  const int k00 = tj * tnx + ti;
  const long carried = (long)sediment[i];

  if (age[i] > lifespan[i]) {  // evaporation: deposit and leave
    const long deposited = (long)floor((float)carried * EROSION_DEPOSIT_FRACTION);
    const long kept = min(deposited, carried);
    spread_quanta(delta, k00, tnx, fx, fz, kept, 1);
    atom_add(&counters[COUNTER_LOST_SEDIMENT], carried - kept);
    atom_inc(&counters[COUNTER_EVAPORATED]);
    sediment[i] = 0;
    id[i] |= DEAD_FLAG;
    return;
  }
  const SurfacePoint s = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, x[i], z[i]);
  if (y[i] - s.height > EROSION_CONTACT_DISTANCE) return;

  const float h00 = terrain_height[k00], h10 = terrain_height[k00 + 1];
  const float h01 = terrain_height[k00 + tnx], h11 = terrain_height[k00 + tnx + 1];
  const float relief = fmax(fmax(h00, h10), fmax(h01, h11)) - fmin(fmin(h00, h10), fmin(h01, h11));
  const float limit = EROSION_LIMIT_FRACTION * tcell * tcell * relief;  // m³
  const float quantum = EROSION_VOLUME_QUANTUM;                            // m³

#if EROSION_MODEL == 0
  const float3 vel = (float3)(vx[i], vy[i], vz[i]);
  const float3 vt = vel - dot(vel, s.normal) * s.normal;
  const float sin_slope = sqrt(fmax(0.0f, 1.0f - s.normal.y * s.normal.y));
  // Flow depth in particle layers: the neighbours of a particle in one flat layer number about
  // π(2h)²/dx² − 1 = EROSION_LAYER_NEIGHBOURS; more means deeper, concentrated flow.
  const float layers = fmax(1.0f, (neighbours[i] + 1.0f) / (EROSION_LAYER_NEIGHBOURS + 1.0f));
  const float capacity = EROSION_CAPACITY * EROSION_PARTICLE_VOLUME * length(vt) *
                         fmax(sin_slope, EROSION_SIN_MIN_SLOPE) * pow(layers, EROSION_DEPTH_EXPONENT);
  const float carried_m3 = (float)carried * quantum;
  if (carried_m3 < capacity) {
    const float amount = fmin(EROSION_ERODE_RATE * (capacity - carried_m3) * dt_e, limit);
    const long q = (long)floor(amount / quantum);
    if (q > 0 && carried + q < 0x7fffffffL) {
      spread_quanta(delta, k00, tnx, fx, fz, q, -1);
      sediment[i] = (int)(carried + q);
      contacts[i] += 1;
    }
  } else {
    const float amount = EROSION_DEPOSIT_RATE * (carried_m3 - capacity) * dt_e;
    const long q = min(carried, (long)floor(amount / quantum));
    if (q > 0) {
      spread_quanta(delta, k00, tnx, fx, fz, q, 1);
      sediment[i] = (int)(carried - q);
    }
  }
#else
  if ((contacts[i] & ~TOUCHING_FLAG) < EROSION_CAPACITY_CONTACTS) {
    const float amount = fmin(EROSION_ACIDITY * tcell * tcell, limit);
    const long q = (long)floor(amount / quantum);
    if (q > 0 && carried + q < 0x7fffffffL) {
      spread_quanta(delta, k00, tnx, fx, fz, q, -1);
      sediment[i] = (int)(carried + q);
      contacts[i] += 1;
    }
  }
#endif
}
