// SPDX-License-Identifier: MIT
// Kick-drift-kick leapfrog (physics.md §2) with the density integrated like the position:
//   kick:   v += a·dt/2                   (a from the last force pass; the drift kernel's first act)
//   drift:  x_new = x + v·dt, age += dt   (then the walls and the terrain contact, below)
//   ρ:      ρ += (dρ/dt)·dt               (sph_continuity.cl, with the drift's actual displacements)
//   kick:   v += a·dt/2                   (a at the new x, ρ: sph_forces.cl; in step_stats)
// so the force pass sees x and ρ of the same instant, and ρ changes exactly as the particles
// actually moved, also where the contact stopped them.
//
// After the drift: vertical walls at the domain edges reflect a particle, or, without walls, a
// particle that leaves the domain is marked dead (removed at the next sort) and its sediment
// booked as outflow. Then the step's segment is tested against the contact surface (collide.cl):
// at a hit the particle's velocity into the surface reverses, scaled by the restitution, and it
// moves on along the surface for the rest of the step (tested once more); a particle resting on the
// surface (within ε) is in contact from the start of the step. A particle found below the surface
// without a contact (the terrain rose under it) is put back on it and counted as a projection.
// Every particle of the water column on the bed (touching it, or with its lowest point within the
// local water depth D of it) feels the bed friction of shallow-water flow, Manning's law:
//   τ_b = ρ g n² |u|² / D^(1/3) over the bed area V/D its water covers, so
//   du/dt = −τ_b (V/D) / (ρ V) = −g n² |u| u / D^(4/3)   (along the bed),
// applied implicitly (u ← u / (1 + dt g n² |u| / D^(4/3))), so it only ever slows the flow. D is
// the water depth on the bed at the end of the last step (water_depth.cl); g n² / D^(4/3) comes from
// bed_friction_factors, launched just before the drift. In steady flow this is Manning's
// equation, u = D^(2/3) S^(1/2) / n, and τ_b = ρ g D S.
// Units: m, s. Compile-time constants (host -D): SPH_WALLS, SPH_SURFACE_EPS, SPH_RESTITUTION,
// SPH_CONTACT_RADIUS, SPH_MANNING_G_N2 (g n², m^(1/3)), SPH_GRAVITY.

inline float kicked(float v, float a, float half_dt) { return v + a * half_dt; }

// What the continuity pass (sph_continuity.cl) needs of the drift, once per particle: the drift's
// midpoint (x(n) + x(n+1))/2, its velocity (x(n+1) − x(n))/dt, the displacement the particle
// actually made, and the volume m/ρ(n) (into the store's spare buffers). Written by the drift,
// which has both ends of the step at hand: no launch of its own.
inline void write_continuity_inputs(uint i, float3 p, float3 p_new, float dt, float rho, __global float* mid_x,
                                    __global float* mid_y, __global float* mid_z, __global float* drift_vx,
                                    __global float* drift_vy, __global float* drift_vz, __global float* volume) {
  const float inv_dt = 1.0f / dt;
  const float3 step = p_new - p;
  const float3 mid = p + 0.5f * step;
  const float3 v = step * inv_dt;
  mid_x[i] = mid.x;
  mid_y[i] = mid.y;
  mid_z[i] = mid.z;
  drift_vx[i] = v.x;
  drift_vy[i] = v.y;
  drift_vz[i] = v.z;
  volume[i] = SPH_MASS / rho;
}

// The bed friction's factor k = g n² / D^(4/3) (1/m) for water of depth D (m), D ≥ 10⁻⁶ m.
#define BED_FRICTION_DEPTH_FLOOR 1e-6f
#define BED_FRICTION_FACTOR(depth) (SPH_MANNING_G_N2 / ((depth) * cbrt(depth)))

// Every particle's bed friction factor, LANES particles a work-item (common.cl), before the drift
// reads them (SphSolver: into the free buffer the continuity pass later writes ρ(n+1) to). PoCL
// turns a cbrt() of one float into a call of a scalar library routine, even in a kernel it widens:
// about a third of the drift's time when the drift took the root itself. A cbrt() of a vector is
// its vector routine, which gives the scalar one's bits (the test checks) at a tenth of the time.
__kernel void bed_friction_factors(const __global float* depth, const uint n, __global float* factor) {
  const uint first = get_global_id(0) * LANES;
  if (first >= n) return;
  if (first + LANES <= n) {
    const floatv d = fmax(LOADV(get_global_id(0), depth), BED_FRICTION_DEPTH_FLOOR);
    STOREV(BED_FRICTION_FACTOR(d), get_global_id(0), factor);
    return;
  }
  // The last work-item's spare lanes read the last particle. The bound is a vector: Oclgrind 21.10
  // (scripts/oclgrind-check.sh) gets min(int8, int) wrong in some lanes.
  const intv k = min((int)first + LANE_INDEX, (intv)((int)n - 1));
  const floatv d = fmax(GATHER_FLOAT(depth, k), BED_FRICTION_DEPTH_FLOOR);
  float out[LANES];
  STOREV(BED_FRICTION_FACTOR(d), 0, out);
  for (uint l = 0; first + l < n; ++l) factor[first + l] = out[l];
}

// Bed friction on the velocity tangential to the surface of normal n, k from bed_friction_factors.
inline float3 bed_friction(float3 v, float3 n, float k, float dt) {
  const float vn = dot(v, n);
  const float3 vt = v - vn * n;
  return vn * n + vt / (1.0f + dt * k * length(vt));
}

// The contact at fraction t of a drift of length dt, for a particle drifting at v under the
// acceleration a (the leapfrog applies a as kicks at both ends of the step). The impact velocity is
// the one at the hit, v + a·dt·(t − ½); it rebounds (contact_response); if the rebound cannot lift
// it clear of the surface before the step ends, the particle stays on the surface and only the
// tangential part of a acts for the rest of the step. Returns the displacement from the hit over
// the rest of the step and sets v to the drift velocity that the step's closing half kick turns
// into the velocity at the step's end. Timing the rebound this way makes a bounce lose or gain
// energy only at O(dt²), whatever the fraction t (reflecting the drift velocity instead gains or
// loses g·|v|·dt·(1 − 2t) per bounce).
inline float3 rebound(float3* v, float3 a, float3 n, float3 face, float t, float dt) {
  const float3 impact = *v + a * (dt * (t - 0.5f));
  float3 out = contact_response_on_face(impact, n, face);
  const float remaining = (1.0f - t) * dt;
  float3 a_rest = a;
  const float an = dot(a, n), vn = dot(out, n);
  if (an < 0.0f && vn + an * remaining < 0.0f) {  // cannot leave the surface: it holds the particle
    a_rest = a - an * n;
    out -= vn * n;
  }
  *v = out + a_rest * (dt * (0.5f - t));
  return out * remaining + a_rest * (0.5f * remaining * remaining);
}

__kernel void drift(const __global float* x, const __global float* y, const __global float* z, __global float* vx,
                    __global float* vy, __global float* vz, __global float* age, __global int* sediment,
                    __global uint* contacts, __global uint* id, const __global float* ax, const __global float* ay, const __global float* az,
                    const __global float* depth, const __global float* friction, const __global float* rho,
                    __global float* x_new,
                    __global float* y_new, __global float* z_new, const uint n, const float dt,
                    const __global float* terrain_contact, const __global float* terrain_normal, const int tnx,
                    const int tny, const float tcell, const float domain_x, const float domain_z,
                    volatile __global long* counters, __global float* mid_x, __global float* mid_y,
                    __global float* mid_z, __global float* drift_vx, __global float* drift_vy,
                    __global float* drift_vz, __global float* volume) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float half_dt = 0.5f * dt;
  float3 v = (float3)(kicked(vx[i], ax[i], half_dt), kicked(vy[i], ay[i], half_dt), kicked(vz[i], az[i], half_dt));
  const float3 start = (float3)(x[i], y[i], z[i]);
  float3 p = start + v * dt;
  age[i] += dt;

  const float wall = SPH_CONTACT_RADIUS;
#if SPH_WALLS
  if (p.x < wall) { p.x = wall; v.x = fabs(v.x) * SPH_RESTITUTION; }
  if (p.x > domain_x - wall) { p.x = domain_x - wall; v.x = -fabs(v.x) * SPH_RESTITUTION; }
  if (p.z < wall) { p.z = wall; v.z = fabs(v.z) * SPH_RESTITUTION; }
  if (p.z > domain_z - wall) { p.z = domain_z - wall; v.z = -fabs(v.z) * SPH_RESTITUTION; }
#else
  if (p.x < 0.0f || p.x > domain_x || p.z < 0.0f || p.z > domain_z) {
    // Outflow: the particle leaves with its sediment, which the mass balance books as outflow.
    id[i] |= DEAD_FLAG;
    atom_inc(&counters[COUNTER_OUTFLOW_PARTICLES]);
    atom_add(&counters[COUNTER_OUTFLOW_SEDIMENT], (long)sediment[i]);
    sediment[i] = 0;
    x_new[i] = p.x;
    y_new[i] = p.y;
    z_new[i] = p.z;
    // Still a candidate of the continuity pass until the next sort removes it (its velocity is
    // not read again: every later pass skips a dead particle or runs after that sort).
    write_continuity_inputs(i, start, p, dt, rho[i], mid_x, mid_y, mid_z, drift_vx, drift_vy, drift_vz, volume);
    return;
  }
#endif
  // Contact with the terrain. A particle that starts the step on the contact surface (within ε)
  // and moves into it is in contact from t = 0 (resting, sliding); otherwise the step's segment is
  // tested for the first crossing. After a hit the particle moves on along the surface for the rest
  // of the step, tested once more for the next face.
  const float3 a = (float3)(ax[i], ay[i], az[i]);
  bool touching = false;
  const SurfacePoint s0 =
      kept_surface(terrain_contact, terrain_normal, tnx, tny, tcell, start.x, start.z);
  // On the surface at the start, and moving into it (along the interpolated normal, or ending the
  // step below the surface: the faces under a particle tilt away from that normal; the surface
  // under the end is sampled only when the normal leaves the question open).
  bool moving_in = false;
  if (start.y - s0.height <= SPH_SURFACE_EPS) {
    moving_in = dot(v, s0.normal) < 0.0f ||
                p.y < kept_surface(terrain_contact, terrain_normal, tnx, tny, tcell, p.x, p.z)
                          .height;
  }
  if (moving_in) {
    touching = true;
    const float3 face = contact_face_at(terrain_contact, tnx, tny, tcell, start.x, start.z);
    p = start + rebound(&v, a, s0.normal, face, 0.0f, dt);
  } else {
    const TerrainHit hit =
        collide_segment(terrain_contact, terrain_normal, tnx, tny, tcell, start, p - start);
    if (hit.t >= 0.0f) {
      touching = true;
      p = hit.point + rebound(&v, a, hit.normal, hit.face, hit.t, dt);
      const TerrainHit again = collide_segment(terrain_contact, terrain_normal, tnx, tny, tcell,
                                               hit.point + SPH_SURFACE_EPS * hit.normal, p - hit.point);
      if (again.t >= 0.0f) {
        v = contact_response_on_face(v, again.normal, again.face);
        p = again.point;
      }
    }
  }
  const SurfacePoint s =
      kept_surface(terrain_contact, terrain_normal, tnx, tny, tcell, p.x, p.z);
  if (p.y < s.height) {
    // In contact, a particle ends on the surface (a slide over a bend, rounding). Otherwise it is
    // below without having crossed it: the terrain rose under it. Either way it goes back up, but
    // only the second case is a projection, counted: the contact should leave none.
    if (!touching && s.height - p.y > SPH_SURFACE_EPS) atom_inc(&counters[COUNTER_PROJECTIONS]);
    p.y = s.height;
    v = contact_response_on_face(v, s.normal, contact_face_at(terrain_contact, tnx, tny, tcell, p.x, p.z));
    touching = true;
  }
  // Touching: in contact this step, or resting within ε. Bed friction on the water column.
  touching = touching || p.y - s.height <= SPH_SURFACE_EPS;
  const float water_depth = fmax(depth[i], BED_FRICTION_DEPTH_FLOOR);
  if (touching || (p.y - s.height) * s.normal.y <= water_depth) v = bed_friction(v, s.normal, friction[i], dt);
  // A collision is an arrival: touching now, not at the end of the last step (a particle that
  // rests or slides on the ground stays in one contact).
  const uint flags = contacts[i];
  if (touching && !(flags & TOUCHING_FLAG)) atom_inc(&counters[COUNTER_COLLISIONS]);
  contacts[i] = touching ? (flags | TOUCHING_FLAG) : (flags & ~TOUCHING_FLAG);
  x_new[i] = p.x;
  y_new[i] = p.y;
  z_new[i] = p.z;
  vx[i] = v.x;
  vy[i] = v.y;
  vz[i] = v.z;
  write_continuity_inputs(i, start, p, dt, rho[i], mid_x, mid_y, mid_z, drift_vx, drift_vy, drift_vz, volume);
}

// The step's closing half kick (`kick` 1: v += a·half_dt; 0 before the first step), then the
// health and time-step statistics of the state, one row of 6 floats per block of particles:
// max |v|², max |a|², min ρ, max ρ, number of non-finite values, max |dρ/dt|.
// The host reduces the rows (max and min do not depend on order). One launch for both: on a CPU
// device each launch costs a wake-up of every worker thread.
// Block b takes the particles b·chunk_stride + k·stride, k < chunk: a contiguous run on a CPU
// (chunk_stride = chunk, stride = 1), every blocks-th particle on a GPU (1 and blocks), so that
// neighbouring work-items read neighbouring particles.
__kernel void step_stats(__global float* vx, __global float* vy, __global float* vz, const __global float* ax,
                         const __global float* ay, const __global float* az, const __global float* rho,
                         const __global float* drho, const uint n, const uint chunk, const uint chunk_stride,
                         const uint stride, const uint blocks, const uint kick, const float half_dt,
                         __global float* stats) {
  const uint block = get_global_id(0);
  if (block >= blocks) return;
  float v2max = 0.0f, a2max = 0.0f, rmin = INFINITY, rmax = -INFINITY, bad = 0.0f, drmax = 0.0f;
  for (uint k = 0, i = block * chunk_stride; k < chunk && i < n; ++k, i += stride) {
    if (kick) {
      vx[i] = kicked(vx[i], ax[i], half_dt);
      vy[i] = kicked(vy[i], ay[i], half_dt);
      vz[i] = kicked(vz[i], az[i], half_dt);
    }
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

// After the terrain changed under the particles (deposition, talus), puts back on the contact
// surface any particle now below it, so no particle ever ends a step below the terrain. A particle
// resting on the surface rides up with it; one that ends more than ε below is counted. A particle
// that left through an open edge this step is not: beyond the edge the surface is the edge's
// height, which a droplet thrown out and down ends below (with dfsph's longer steps, most that
// leave do).
__kernel void project_to_surface(__global float* x, __global float* y, __global float* z, __global float* vx,
                                 __global float* vy, __global float* vz, const __global uint* id, const uint n,
                                 const __global float* terrain_contact, const __global float* terrain_normal,
                                 const int tnx, const int tny, const float tcell, volatile __global long* counters) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  if (id[i] & DEAD_FLAG) return;  // left through an open edge this step: gone at the next sort
  const SurfacePoint s =
      kept_surface(terrain_contact, terrain_normal, tnx, tny, tcell, x[i], z[i]);
  if (y[i] >= s.height) return;
  if (s.height - y[i] > SPH_SURFACE_EPS) atom_inc(&counters[COUNTER_PROJECTIONS]);
  y[i] = s.height;
  const float3 v = contact_response_on_face((float3)(vx[i], vy[i], vz[i]), s.normal,
                                            contact_face_at(terrain_contact, tnx, tny, tcell, x[i], z[i]));
  vx[i] = v.x;
  vy[i] = v.y;
  vz[i] = v.z;
}
