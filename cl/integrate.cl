// SPDX-License-Identifier: MIT
// Kick-drift-kick leapfrog (physics.md §2), density integrated like position:
//   kick_drift: v += a·dt/2, ρ += (dρ/dt)·dt/2, x += v·dt, age += dt, then the boundary response
//   kick:       v += a·dt/2, ρ += (dρ/dt)·dt/2   (with the rates at the new positions)
// Boundaries after the drift: vertical walls at the domain edges reflect a particle, or, without
// walls, a particle that leaves the domain is marked dead (removed at the next sort) and its
// sediment booked as outflow. Then the step's segment is tested against the terrain triangles
// (collide.cl); a particle still below the surface (the terrain rose under it) is projected up.
// Units: m, s. Compile-time constants (host -D): SPH_WALLS, SPH_SURFACE_EPS, SPH_RESTITUTION,
// SPH_FRICTION.

__kernel void kick_drift(__global float* x, __global float* y, __global float* z, __global float* vx,
                         __global float* vy, __global float* vz, __global float* rho, __global float* age,
                         __global int* sediment, __global uint* id, const __global float* ax,
                         const __global float* ay, const __global float* az, const __global float* drho,
                         const uint n, const float dt, const __global float* terrain_height,
                         const __global float* terrain_normal, const int tnx, const int tny, const float tcell,
                         const float domain_x, const float domain_z, volatile __global long* counters) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float half_dt = 0.5f * dt;
  float3 v = (float3)(vx[i] + ax[i] * half_dt, vy[i] + ay[i] * half_dt, vz[i] + az[i] * half_dt);
  rho[i] += drho[i] * half_dt;
  const float3 start = (float3)(x[i], y[i], z[i]);
  float3 p = start + v * dt;
  age[i] += dt;

#if SPH_WALLS
  if (p.x < SPH_SURFACE_EPS) { p.x = SPH_SURFACE_EPS; v.x = fabs(v.x) * SPH_RESTITUTION; }
  if (p.x > domain_x - SPH_SURFACE_EPS) { p.x = domain_x - SPH_SURFACE_EPS; v.x = -fabs(v.x) * SPH_RESTITUTION; }
  if (p.z < SPH_SURFACE_EPS) { p.z = SPH_SURFACE_EPS; v.z = fabs(v.z) * SPH_RESTITUTION; }
  if (p.z > domain_z - SPH_SURFACE_EPS) { p.z = domain_z - SPH_SURFACE_EPS; v.z = -fabs(v.z) * SPH_RESTITUTION; }
#else
  if (p.x < 0.0f || p.x > domain_x || p.z < 0.0f || p.z > domain_z) {
    // Outflow: the particle leaves with its sediment, which the mass balance books as outflow.
    id[i] |= DEAD_FLAG;
    atom_inc(&counters[COUNTER_OUTFLOW_PARTICLES]);
    atom_add(&counters[COUNTER_OUTFLOW_SEDIMENT], (long)sediment[i]);
    sediment[i] = 0;
  }
#endif
  // Continuous collision along the step, then a guard for particles the terrain rose under.
  const TerrainHit hit = collide_segment(terrain_height, terrain_normal, tnx, tny, tcell, start, p - start);
  if (hit.t >= 0.0f) {
    p = hit.point + SPH_SURFACE_EPS * hit.normal;
    v = contact_response(v, hit.normal);
    atom_inc(&counters[COUNTER_COLLISIONS]);
  }
  const SurfacePoint s = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, p.x, p.z);
  if (p.y < s.height + SPH_SURFACE_EPS) {
    p.y = s.height + SPH_SURFACE_EPS;
    v = contact_response(v, s.normal);
    atom_inc(&counters[COUNTER_PROJECTIONS]);
  }
  x[i] = p.x;
  y[i] = p.y;
  z[i] = p.z;
  vx[i] = v.x;
  vy[i] = v.y;
  vz[i] = v.z;
}

__kernel void kick(__global float* vx, __global float* vy, __global float* vz, __global float* rho,
                   const __global float* ax, const __global float* ay, const __global float* az,
                   const __global float* drho, const uint n, const float dt) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float half_dt = 0.5f * dt;
  vx[i] += ax[i] * half_dt;
  vy[i] += ay[i] * half_dt;
  vz[i] += az[i] * half_dt;
  rho[i] += drho[i] * half_dt;
}

// Health and time-step statistics, one row of 6 floats per block of particles:
// max |v|², max |a|², min ρ, max ρ, number of non-finite values, max |dρ/dt|.
// The host reduces the rows (max and min do not depend on order).
__kernel void step_stats(const __global float* vx, const __global float* vy, const __global float* vz,
                         const __global float* ax, const __global float* ay, const __global float* az,
                         const __global float* rho, const __global float* drho, const uint n, const uint chunk,
                         __global float* stats) {
  const uint block = get_global_id(0);
  const uint begin = block * chunk;
  const uint end = min(begin + chunk, n);
  float v2max = 0.0f, a2max = 0.0f, rmin = INFINITY, rmax = -INFINITY, bad = 0.0f, drmax = 0.0f;
  for (uint i = begin; i < end; ++i) {
    const float v2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
    const float a2 = ax[i] * ax[i] + ay[i] * ay[i] + az[i] * az[i];
    if (!isfinite(v2) || !isfinite(a2) || !isfinite(rho[i]) || !isfinite(drho[i])) {
      bad += 1.0f;
      continue;
    }
    v2max = fmax(v2max, v2);
    a2max = fmax(a2max, a2);
    rmin = fmin(rmin, rho[i]);
    rmax = fmax(rmax, rho[i]);
    drmax = fmax(drmax, fabs(drho[i]));
  }
  __global float* row = stats + 6 * block;
  row[0] = v2max;
  row[1] = a2max;
  row[2] = rmin;
  row[3] = rmax;
  row[4] = bad;
  row[5] = drmax;
}

// After the terrain changed under the particles (deposition, talus), puts back on the surface any
// particle now below it, so no particle ever ends a step below the terrain.
__kernel void project_to_surface(__global float* x, __global float* y, __global float* z, __global float* vx,
                                 __global float* vy, __global float* vz, const uint n,
                                 const __global float* terrain_height, const __global float* terrain_normal,
                                 const int tnx, const int tny, const float tcell, volatile __global long* counters) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const SurfacePoint s = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, x[i], z[i]);
  if (y[i] >= s.height + SPH_SURFACE_EPS) return;
  y[i] = s.height + SPH_SURFACE_EPS;
  const float3 v = contact_response((float3)(vx[i], vy[i], vz[i]), s.normal);
  vx[i] = v.x;
  vy[i] = v.y;
  vz[i] = v.z;
  atom_inc(&counters[COUNTER_PROJECTIONS]);
}
