// SPDX-License-Identifier: MIT
// SPH momentum (physics.md §2) at the drifted state (x, ρ at step n+1; v at n+½): Tait pressure and
// Monaghan artificial viscosity,
//   dv_i/dt = −Σ_j m (p_i/ρ_i² + p_j/ρ_j² + Π_ij) ∇_iW_ij + g
//   p = B((ρ/ρ0)^7 − 1), B = c0² ρ0 / 7;  Π_ij = −α c0 μ_ij / ρ̄_ij when v_ij·x_ij < 0,
//   μ_ij = h v_ij·x_ij / (|x_ij|² + 0.01h²)
// The density is integrated separately (sph_continuity.cl), with the drift. The terrain and the
// tank walls act through sph_boundary.cl, in pairs with their continuity terms.
// Units: m, s, kg. Compile-time constants (host -D): SPH_H, SPH_MASS, SPH_RHO0, SPH_C0, SPH_B,
// SPH_ALPHA_VISC, SPH_GRAVITY, SPH_CLAMP_NEGATIVE_PRESSURE, SPH_WALLS.

inline float tait_pressure(float rho) {
  const float r = rho * (1.0f / SPH_RHO0);
  const float r2 = r * r;
  const float p = SPH_B * (r2 * r2 * r2 * r - 1.0f);
#if SPH_CLAMP_NEGATIVE_PRESSURE
  return max(p, 0.0f);
#else
  return p;
#endif
}

// The terrain's completion of the kernel (sph_boundary.cl) for a particle at distance d along the
// unit normal n: the mirror of its pressure, 2 p G(d)/ρ n, and the support of the pressure gradient
// extrapolated beyond, −M(d)·∇p/ρ with ∇p = (I − M(d))⁻¹·gp (gp measured over the rest of the
// kernel; both matrices have n as an eigenvector: a on n, b across).
inline float3 wall_force(float d, float3 n, float p_over_rho, float3 gp_over_rho) {
  const float g = wall_integral(d);
  if (g == 0.0f) return (float3)(0.0f, 0.0f, 0.0f);
  const float a = wall_moment_normal(d), b = wall_moment_tangent(d);
  const float gn = dot(gp_over_rho, n);
  const float3 gt = gp_over_rho - gn * n;
  return n * (2.0f * p_over_rho * g) - (a / (1.0f - a) * gn) * n - (b / (1.0f - b)) * gt;
}

// One neighbour's (or ghost's) contribution: pressure and viscosity to acc, its pressure difference
// to the gradient sum gp = Σ_j V_j (p_j − p_i) ∇_iW_ij, its kernel to the Shepard sum.
inline void pair_force(float3 xij, float3 vij, float rhoi, float pres_i, float pi_over_rho2, float rhoj,
                       float pres_j, float3* acc, float3* gp, float* shepard) {
  const float r2 = dot(xij, xij);
  const float r = sqrt(r2);
  const float f = wendland_grad_factor(r);
  const float vdotx = dot(vij, xij);
  const float eta2 = 0.01f * SPH_H * SPH_H;
  float visc = 0.0f;
  if (vdotx < 0.0f) {
    const float mu = SPH_H * vdotx / (r2 + eta2);
    visc = -SPH_ALPHA_VISC * SPH_C0 * mu / (0.5f * (rhoi + rhoj));
  }
  *acc -= (SPH_MASS * (pi_over_rho2 + pres_j / (rhoj * rhoj) + visc) * f) * xij;
  *gp += (SPH_MASS / rhoj * (pres_j - pres_i) * f) * xij;
  *shepard += SPH_MASS / rhoj * wendland_w(r);
}

__kernel void sph_forces(const __global float* x, const __global float* y, const __global float* z,
                         const __global float* vx, const __global float* vy, const __global float* vz,
                         const __global float* rho, const uint n, const float ox, const float oy, const float oz,
                         const float inv_cell, const int gx, const int gy, const int gz,
                         const __global uint* cell_start, const __global uint* cell_end,
                         const __global float* terrain_height, const __global float* terrain_normal,
                         const int tnx, const int tny, const float tcell, const float domain_x,
                         const float domain_z, __global float* ax, __global float* ay, __global float* az) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const float3 pi = (float3)(x[i], y[i], z[i]);
  const float3 vi = (float3)(vx[i], vy[i], vz[i]);
  const float rhoi = rho[i];
  const float pres_i = tait_pressure(rhoi);
  const float pi_over_rho2 = pres_i / (rhoi * rhoi);
  const float support2 = 4.0f * SPH_H * SPH_H;
#if SPH_WALLS
  const TankWalls walls = tank_walls(pi, domain_x, domain_z);
#endif

  const SurfacePoint floor = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, pi.x, pi.z);

  float3 acc = (float3)(0.0f, 0.0f, 0.0f), acc_ghosts = (float3)(0.0f, 0.0f, 0.0f);
  float3 gp = (float3)(0.0f, 0.0f, 0.0f);  // Σ_j V_j (p_j − p_i) ∇_iW_ij, ghosts included
  float shepard = 0.0f;                    // Σ_{j≠i} V_j W_ij, ghosts included
  NEIGHBOUR_LOOP_BEGIN(pi, grid, cell_start, cell_end)
  const float3 pj = (float3)(x[j], y[j], z[j]);
  const float3 xij = pi - pj;
  if (dot(xij, xij) < support2) {
    const float3 vj = (float3)(vx[j], vy[j], vz[j]);
    const float rhoj = rho[j];
    const float pres_j = tait_pressure(rhoj);
    if (j != i) {
      pair_force(xij, vi - vj, rhoi, pres_i, pi_over_rho2, rhoj, pres_j, &acc, &gp, &shepard);
    }
#if SPH_WALLS
    GHOST_LOOP_BEGIN(walls, pj, vj)
    const float3 xig = pi - ghost_;
    if (dot(xig, xig) < support2)
      pair_force(xig, vi - ghost_v_, rhoi, pres_i, pi_over_rho2, rhoj, pres_j, &acc_ghosts, &gp, &shepard);
    GHOST_LOOP_END
#endif
  }
  NEIGHBOUR_LOOP_END

  // The terrain under the particle and the tank walls, scaled by the fluid fullness θ.
  const float d = (pi.y - floor.height) * floor.normal.y;
  const float theta = fluid_fullness(shepard, d, rhoi);
  acc += theta * (acc_ghosts + wall_force(d, floor.normal, pres_i / rhoi, gp / rhoi));
  ax[i] = acc.x;
  ay[i] = acc.y - SPH_GRAVITY;
  az[i] = acc.z;
}
