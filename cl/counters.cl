// SPDX-License-Identifier: MIT
// Event counters every step kernel may bump: 64-bit integers (cl_khr_int64_base_atomics), so their
// totals are exact and independent of the order of the work-items. The host reads them as
// SphCounters.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable

#define COUNTER_PROJECTIONS 0        // particles found below the surface and put back on it
#define COUNTER_OUTFLOW_PARTICLES 1  // particles that left through an open edge
#define COUNTER_COLLISIONS 2         // arrivals on the terrain (Möller–Trumbore hits, landings within ε)
#define COUNTER_OUTFLOW_SEDIMENT 3   // sediment quanta carried out through open edges
#define COUNTER_EVAPORATED 4         // particles that reached their lifespan
#define COUNTER_LOST_SEDIMENT 5      // quanta not deposited on evaporation (erosion.deposit_fraction < 1)
#define COUNTER_COUNT 6
