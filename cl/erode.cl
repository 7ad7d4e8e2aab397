// SPDX-License-Identifier: MIT
// Erosion, deposition and evaporation (physics.md §4; docs/erosion.md), per particle after the
// drift. Sediment is counted in bed volume (m³ of terrain), as integer counts of the volume quantum
// Q = q·cell² (q the height quantum), so every exchange moves exactly what the particle gains or
// loses.
//
// The stream-power model (EROSION_MODEL 0): Foster & Meyer's (1975) coupling of detachment and
// transport capacity, as in WEPP's rill equations (Nearing et al. 1989), driven by the power the
// flow spends on its bed (Bagnold 1966; Nearing et al. 1997 found stream power the best predictor of
// rill detachment). A particle of the water column on the bed (touching the ground, or its lowest
// point, along the surface normal, within the local water depth D of the terrain; D from
// water_depth.cl, measured at the end of the last step) stands for the water over the bed area
// V/D, and exchanges with that area:
//   bed shear stress (Manning, the SPH bed friction's law):  τ = ρ0 g n² |u_t|² / D^(1/3)
//   stream power spent on the bed:   ω = τ |u_t|     (W/m²; ρ0 g q S in steady flow)
//   detachment capacity:             D_c = K_ω (ω − ω_c)⁺ / ρ_b          (m/s of bed)
//   transport capacity: k_T ω per unit width, as a concentration of the water,
//                       c_T = min(k_T ρ0 g S / ρ_b, c_max)    (its steady-flow value: S the sine
//                       of the bed's slope along the flow, 0 where the water climbs; a unit of
//                       water's capacity is set by the slope, which no particle size or depth
//                       estimate can bias)
//   c = s / V the particle's load per water volume;
//   c < c_T: detachment  E = D_c (1 − c/c_T),   uptake ΔV = E (V/D) dt, at most (c_T − c) V
//   c > c_T: deposition  E = w_s (c − c_T),     drop   ΔV = E (V/D) dt, at most (c − c_T) V
// Rates are per second of flow and per unit area of bed: the total over the bed does not depend on
// the particle size where the flow is resolved (the water on a footprint is several particles);
// the caps keep a step from overshooting.
// The morphological factor MF (Roelvink 2006) runs the bed MF times faster than the water: the
// load is kept in accelerated bed volume, c̃ = MF c, so the detachment rate and the capacity (c_T,
// c_max) are multiplied by MF and the deposition w_s c̃ follows by itself; the water is unchanged.
// The acidity model (EROSION_MODEL 1, Fritz 2016): each contact erodes `acidity`·cell² until the
// particle has eroded `capacity_contacts` times. The bed-load model (EROSION_MODEL 2): see below.
// Evaporation: at the end of its lifespan a particle deposits its load (deposit_fraction of it;
// the rest is booked as lost) and is removed.
//
// Every amount is spread over the footprint (footprint.cl): the vertices within FOOTPRINT_RADIUS (at
// least the smoothing length's support) of the particle, with smooth separable weights, so no event builds a spike or
// digs a pit on one tile. Amounts become whole quanta by stochastic rounding and are placed by
// systematic sampling (counter-based random numbers of the particle and the step): unbiased
// however small a step's exchange is, exact in total, and reproducible. Heights change only when terrain_apply adds the deltas.
// Compile-time constants (host -D): EROSION_*, FOOTPRINT_RADIUS.

#define EROSION_STREAM 0x65726f64UL  // "erod"

// Adds sign·quanta over the footprint of (x, z) (spread_quanta, weighted by `factor` where not null)
// and marks the terrain tiles the footprint reaches (its off-grid fallback vertex included), for
// terrain_apply.
inline void land_quanta(volatile __global long* delta, __global uint* changed, int tiles_x, int nx, int ny,
                        float cell, float x, float z, long quanta, long sign, float u, const __global float* factor,
                        float factor_mean) {
  if (quanta == 0) return;
  spread_quanta(delta, nx, ny, cell, x, z, quanta, sign, u, factor, factor_mean);
  const float last_i = (float)(nx - 1), last_j = (float)(ny - 1);
  const int i0 = (int)clamp(floor((x - FOOTPRINT_RADIUS) / cell), 0.0f, last_i);
  const int i1 = (int)clamp(ceil((x + FOOTPRINT_RADIUS) / cell), 0.0f, last_i);
  const int j0 = (int)clamp(floor((z - FOOTPRINT_RADIUS) / cell), 0.0f, last_j);
  const int j1 = (int)clamp(ceil((z + FOOTPRINT_RADIUS) / cell), 0.0f, last_j);
  mark_changed_tiles(changed, tiles_x, i0, i1, j0, j1);
}

// Random numbers of a particle's exchange in one step: draw 0 rounds the volume, draw 1 places the
// quanta.
inline float exchange_random(ulong seed, uint id, ulong step, uint draw) {
  return rng_uniform(seed, EROSION_STREAM + draw, (step << 32) | (ulong)id);
}

// A volume (m³) as whole quanta: floor(volume/Q + u), u uniform in [0, 1), so the expected count is
// exactly volume/Q however small the volume.
inline long stochastic_quanta(float volume, float u) {
  return (long)floor(volume * (1.0f / EROSION_VOLUME_QUANTUM) + u);
}

__kernel void erode_exchange(const __global float* x, const __global float* y, const __global float* z,
                             const __global float* vx, const __global float* vy, const __global float* vz,
                             __global int* sediment, __global uint* contacts, const __global float* age,
                             const __global float* lifespan, __global uint* id, const __global float* depth,
                             const uint n, const float dt, const float morphological_factor,
                             const ulong seed, const ulong step_index,
                             const __global float* terrain_height, const __global float* terrain_normal,
                             const int tnx, const int tny, const float tcell, volatile __global long* delta,
                             __global uint* changed, const int tiles_x, volatile __global long* counters,
                             const __global float* erodibility) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  if (id[i] & DEAD_FLAG) return;
  const float px = x[i], pz = z[i];
  const long carried = (long)sediment[i];

  if (age[i] > lifespan[i]) {  // evaporation: deposit and leave
    const long kept = min(carried, (long)floor((float)carried * EROSION_DEPOSIT_FRACTION));
    land_quanta(delta, changed, tiles_x, tnx, tny, tcell, px, pz, kept, 1,
                exchange_random(seed, id[i], step_index, 1), 0, 1.0f);
    atom_add(&counters[COUNTER_LOST_SEDIMENT], carried - kept);
    atom_inc(&counters[COUNTER_EVAPORATED]);
    sediment[i] = 0;
    id[i] |= DEAD_FLAG;
    return;
  }
  const SurfacePoint s = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, px, pz);
  const float gap = (y[i] - s.height) * s.normal.y - EROSION_PARTICLE_RADIUS;  // along the normal
  const float water_depth = fmax(depth[i], 1e-6f);                            // D, m
  // On the bed: touching the ground (as the drift's bed friction decides), or within the water on
  // it. A film's D can be thinner than the ε a resting particle keeps above the ground.
  if (!(contacts[i] & TOUCHING_FLAG) && gap > water_depth) return;  // a falling drop

  // The exposed material's erodibility over the particle's footprint (docs/layers.md): its mean is a
  // factor on the detachment (never on the deposition), and the quanta detached come from the
  // footprint's vertices in proportion to their erodibility, none from a frozen one.
#if GROUND
  const float bed_factor = footprint_mean_float(erodibility, tnx, tny, tcell, px, pz);
  const __global float* bed_field = erodibility;
#else
  const float bed_factor = 1.0f;
  const __global float* bed_field = 0;
#endif
#if EROSION_MODEL == 0
  const float3 vel = (float3)(vx[i], vy[i], vz[i]);
  const float3 along_bed = vel - dot(vel, s.normal) * s.normal;
  const float speed = length(along_bed);
  const float tau = EROSION_RHO_G_N2 * speed * speed / cbrt(water_depth);  // Pa
  const float excess = fmax(tau * speed - EROSION_CRITICAL_POWER, 0.0f);    // W/m²
  // The bed's slope along the flow, the S of ω = ρ0 g q S: the height the water loses per metre of
  // its path. Water climbing out of a hollow has none, so it drops its load there instead of
  // deepening the hollow; across a slope it has less than the steepest descent.
  const float sin_slope = speed > 0.0f ? fmax(0.0f, -along_bed.y / speed) : 0.0f;
  const float capacity =
      morphological_factor * fmin(EROSION_TRANSPORT_SLOPE * sin_slope, EROSION_MAX_CONCENTRATION);
  const float area = EROSION_PARTICLE_VOLUME / water_depth;  // the bed under this water, m²
  const float load = (float)carried * EROSION_VOLUME_QUANTUM;                         // m³
  const float concentration = load / EROSION_PARTICLE_VOLUME;                         // c
  if (concentration < capacity) {
    const float rate =
        morphological_factor * EROSION_DETACHMENT * excess * (1.0f - concentration / capacity) * bed_factor;
    const float amount = fmin(rate * area * dt, (capacity - concentration) * EROSION_PARTICLE_VOLUME);
    const long q = stochastic_quanta(amount, exchange_random(seed, id[i], step_index, 0));
    if (q > 0 && carried + q < 0x7fffffffL) {
      land_quanta(delta, changed, tiles_x, tnx, tny, tcell, px, pz, q, -1,
                  exchange_random(seed, id[i], step_index, 1), bed_field, bed_factor);
      sediment[i] = (int)(carried + q);
    }
  } else {
    const float rate = EROSION_SETTLING * (concentration - capacity);  // m/s
    const float amount = fmin(rate * area * dt, load - capacity * EROSION_PARTICLE_VOLUME);
    const long q = min(carried, stochastic_quanta(amount, exchange_random(seed, id[i], step_index, 0)));
    if (q > 0) {
      land_quanta(delta, changed, tiles_x, tnx, tny, tcell, px, pz, q, 1,
                  exchange_random(seed, id[i], step_index, 1), 0, 1.0f);
      sediment[i] = (int)(carried - q);
    }
  }
#elif EROSION_MODEL == 2
  // Bed load: the flow over the particle's bed area V/D rolls q = q* sqrt(R g d³) of grains per metre
  // of width (Wong & Parker's q* = 3.97 (θ − θc)^(3/2), θ the Shields stress of the Manning shear);
  // the grains in motion over a unit of bed are q / u of grains, q / (u (1 − p)) of bed, so the
  // particle's water carries c_B = MF q / (u D (1 − p)) of bed per volume at equilibrium. Its load
  // relaxes to c_B over the adaptation length: the fraction 1 − exp(−Δt max(u, w_s) / L_a) of the
  // difference each step (picked up at the footprint's erodibility, or dropped), so still water
  // drops its load at the settling velocity's pace.
  const float3 vel = (float3)(vx[i], vy[i], vz[i]);
  const float3 along_bed = vel - dot(vel, s.normal) * s.normal;
  const float speed = length(along_bed);
  const float tau = EROSION_RHO_G_N2 * speed * speed / cbrt(water_depth);  // Pa
  const float shields = tau / ((SED_GRAIN_DENSITY - EROSION_RHO0) * EROSION_GRAVITY * SED_GRAIN_DIAMETER);
  const float excess = fmax(shields - SED_CRITICAL_SHIELDS, 0.0f);
  const float q = SED_WONG_PARKER * excess * sqrt(excess) * sqrt(SED_SUBMERGED_RD * EROSION_GRAVITY) *
                  SED_GRAIN_DIAMETER;  // m² of grains per s
  const float capacity =
      speed > 0.0f ? fmin(morphological_factor * q / (speed * water_depth * (1.0f - SED_POROSITY)),
                          morphological_factor * EROSION_MAX_CONCENTRATION)
                   : 0.0f;
  const float load = (float)carried * EROSION_VOLUME_QUANTUM;  // m³ of bed
  const float relaxed = -expm1(-dt * fmax(speed, EROSION_SETTLING) / SED_ADAPTATION_LENGTH);
  const float difference = capacity * EROSION_PARTICLE_VOLUME - load;
  if (difference > 0.0f) {
    const long taken = stochastic_quanta(difference * relaxed * bed_factor, exchange_random(seed, id[i], step_index, 0));
    if (taken > 0 && carried + taken < 0x7fffffffL) {
      land_quanta(delta, changed, tiles_x, tnx, tny, tcell, px, pz, taken, -1,
                  exchange_random(seed, id[i], step_index, 1), bed_field, bed_factor);
      sediment[i] = (int)(carried + taken);
    }
  } else {
    const long dropped = min(carried, stochastic_quanta(-difference * relaxed, exchange_random(seed, id[i], step_index, 0)));
    if (dropped > 0) {
      land_quanta(delta, changed, tiles_x, tnx, tny, tcell, px, pz, dropped, 1,
                  exchange_random(seed, id[i], step_index, 1), 0, 1.0f);
      sediment[i] = (int)(carried - dropped);
    }
  }
#else
  if ((contacts[i] & ~TOUCHING_FLAG) < EROSION_CAPACITY_CONTACTS) {
    const long q = stochastic_quanta(EROSION_ACIDITY * tcell * tcell * bed_factor,
                                     exchange_random(seed, id[i], step_index, 0));
    if (q > 0 && carried + q < 0x7fffffffL) {
      land_quanta(delta, changed, tiles_x, tnx, tny, tcell, px, pz, q, -1,
                  exchange_random(seed, id[i], step_index, 1), bed_field, bed_factor);
      sediment[i] = (int)(carried + q);
      contacts[i] += 1;
    }
  }
#endif
}
