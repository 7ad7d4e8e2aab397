// SPDX-License-Identifier: MIT
// SPH continuity with δ-SPH density diffusion (physics.md §2), integrated with the drift: the
// drift's velocities v_i = (x_i(n+1) − x_i(n))/dt, the displacements the particles actually made
// (after the terrain contact stopped or deflected them), at the midpoints of the drift
// (x(n) + x(n+1))/2, densities of step n: the midpoint rule, so ρ advances with x from the same
// state, to second order (leapfrog, integrate.cl). Pressure is then never
// evaluated from a density that lags the positions (which pumps energy into every oscillation), and
// particles the contact holds still compress as the fluid above them comes closer.
//   dρ_i/dt = Σ_j m v_ij·∇_iW_ij + 2δ h c0 Σ_j (m/ρ_j)(ρ_ij − ρ^H_ij) x_ij·∇_iW_ij / (|x_ij|² + 0.01h²)
//   ρ_i(n+1) = ρ_i(n) + dt · dρ_i/dt
// with ρ_ij = ρ_i − ρ_j and its hydrostatic part ρ^H_ij = ρ0 g (y_j − y_i) / c0²: δ-SPH diffuses
// only the dynamic density (Fourtakas et al. 2019), so a fluid at rest stays at rest where the
// kernel is truncated (free surface, walls).
// The terrain and the tank walls add their terms (sph_boundary.cl), the partners of their
// momentum terms, scaled by the same fluid fullness θ.
// Units: kg/m³/s. Compile-time constants (host -D): SPH_H, SPH_MASS, SPH_RHO0, SPH_C0, SPH_DELTA,
// SPH_GRAVITY, SPH_WALLS.

__kernel void sph_continuity(const __global float* x, const __global float* y, const __global float* z,
                             const __global float* x_new, const __global float* y_new,
                             const __global float* z_new, const __global float* rho, const uint n, const float dt,
                             const float ox, const float oy, const float oz, const float inv_cell, const int gx,
                             const int gy, const int gz, const __global uint* cell_start,
                             const __global uint* cell_end, const __global float* terrain_height,
                             const __global float* terrain_normal, const int tnx, const int tny, const float tcell,
                             const float domain_x, const float domain_z, __global float* drho,
                             __global float* rho_new) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const float3 pi = (float3)(x[i], y[i], z[i]);  // for the cell search
  const float inv_dt = 1.0f / dt;
  const float3 step_i = (float3)(x_new[i], y_new[i], z_new[i]) - pi;
  const float3 vi = step_i * inv_dt;
  const float3 mid_i = pi + 0.5f * step_i;
  const float rhoi = rho[i];
  const float eta2 = 0.01f * SPH_H * SPH_H;
  const float diffusion = 2.0f * SPH_DELTA * SPH_H * SPH_C0;
  const float support2 = 4.0f * SPH_H * SPH_H;
  const float hydrostatic_gradient = SPH_RHO0 * SPH_GRAVITY / (SPH_C0 * SPH_C0);  // kg/m⁴

#if SPH_WALLS
  const TankWalls walls = tank_walls(mid_i, domain_x, domain_z);
#endif
  float drho_i = 0.0f, drho_ghosts = 0.0f;
  float shepard = 0.0f;  // Σ_{j≠i} V_j W_ij, ghosts included
  NEIGHBOUR_LOOP_BEGIN(pi, grid, cell_start, cell_end)
  const float3 pj = (float3)(x[j], y[j], z[j]);
  const float3 step_j = (float3)(x_new[j], y_new[j], z_new[j]) - pj;
  const float3 mid_j = pj + 0.5f * step_j;
  const float3 xij = mid_i - mid_j;
  const float r2 = dot(xij, xij);
  if (r2 < support2) {
    const float3 vj = step_j * inv_dt;
    const float rhoj = rho[j];
    if (j != i) {
      const float r = sqrt(r2);
      const float f = wendland_grad_factor(r);
      const float rho_dynamic = (rhoi - rhoj) + hydrostatic_gradient * xij.y;
      drho_i += SPH_MASS * dot(vi - vj, xij) * f + diffusion * (SPH_MASS / rhoj) * rho_dynamic * (r2 * f) / (r2 + eta2);
      shepard += SPH_MASS / rhoj * wendland_w(r);
    }
#if SPH_WALLS
    GHOST_LOOP_BEGIN(walls, mid_j, vj)
    const float3 xig = mid_i - ghost_;
    const float rg2 = dot(xig, xig);
    if (rg2 < support2) {
      const float rg = sqrt(rg2);
      drho_ghosts += SPH_MASS * dot(vi - ghost_v_, xig) * wendland_grad_factor(rg);
      shepard += SPH_MASS / rhoj * wendland_w(rg);
    }
    GHOST_LOOP_END
#endif
  }
  NEIGHBOUR_LOOP_END

  // The terrain under the particle (the mirrored normal velocity) and the tank walls, scaled by θ.
  const SurfacePoint floor = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, mid_i.x, mid_i.z);
  const float d = (mid_i.y - floor.height) * floor.normal.y;
  const float theta = fluid_fullness(shepard, d, rhoi);
  drho_i += theta * (drho_ghosts - 2.0f * rhoi * dot(vi, floor.normal) * wall_integral(d));
  drho[i] = drho_i;
  rho_new[i] = rhoi + dt * drho_i;
}
