// SPDX-License-Identifier: MIT
// SPH interactions (physics.md §2): in one pass over each particle's neighbours, the continuity
// equation with δ-SPH density diffusion and the momentum equation with Tait pressure and Monaghan
// artificial viscosity. Both rates depend only on the current (x, v, ρ), so one neighbour loop
// serves both (the density is integrated, not summed).
//   dρ_i/dt = Σ_j m v_ij·∇_iW_ij + 2δ h c0 Σ_j (m/ρ_j)(ρ_ij − ρ^H_ij) x_ij·∇_iW_ij / (|x_ij|² + 0.01h²)
//   with ρ_ij = ρ_i − ρ_j and its hydrostatic part ρ^H_ij = ρ0 g (y_j − y_i) / c0²
//   dv_i/dt = −Σ_j m (p_i/ρ_i² + p_j/ρ_j² + Π_ij) ∇_iW_ij + g
//   p = B((ρ/ρ0)^7 − 1), B = c0² ρ0 / 7;  Π_ij = −α c0 μ_ij / ρ̄_ij when v_ij·x_ij < 0,
//   μ_ij = h v_ij·x_ij / (|x_ij|² + 0.01h²)
// Boundaries (the floor, and the vertical walls when enabled) act as planar mirrors: the missing
// half-space of particles, integrated analytically (sph_kernel.cl), with the particle's pressure
// and density plus the hydrostatic gradient (as Adami et al. 2012 extrapolate wall pressure):
//   a += 2 p_i G(d)/ρ_i n − M(d)·g⃗          (pressure mirror, hydrostatic support)
//   dρ/dt += −2 ρ_i (v_i·n) G(d)             (mirrored normal velocity; the mirror's density
//                                             differs only hydrostatically, which δ-SPH ignores)
// Units: m, s, kg. Compile-time constants (host -D): SPH_H, SPH_MASS, SPH_RHO0, SPH_C0, SPH_B,
// SPH_ALPHA_VISC, SPH_DELTA, SPH_GRAVITY, SPH_CLAMP_NEGATIVE_PRESSURE, SPH_WALLS.

#ifndef WALL_TANGENT_SUPPORT
#define WALL_TANGENT_SUPPORT 1.0f
#endif

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

// A planar boundary at distance d along the unit normal n (pointing into the fluid).
inline void wall_response(float d, float3 n, float3 v, float rho, float p, float3* acc, float* drho) {
  const float g = wall_integral(d);
  if (g == 0.0f) return;
  const float3 up = (float3)(0.0f, 1.0f, 0.0f);
  const float a = wall_moment_normal(d), b = wall_moment_tangent(d);
  *acc += n * (2.0f * p * g / rho) + SPH_GRAVITY * (a * n.y * n + WALL_TANGENT_SUPPORT * b * (up - n.y * n));
  *drho -= 2.0f * rho * dot(v, n) * g;
}

__kernel void sph_forces(const __global float* x, const __global float* y, const __global float* z,
                         const __global float* vx, const __global float* vy, const __global float* vz,
                         const __global float* rho, const uint n, const float ox, const float oy, const float oz,
                         const float inv_cell, const int gx, const int gy, const int gz,
                         const __global uint* cell_start, const __global uint* cell_end,
                         const __global float* terrain_height, const __global float* terrain_normal,
                         const int tnx, const int tny, const float tcell, const float domain_x,
                         const float domain_z, __global float* ax, __global float* ay, __global float* az,
                         __global float* drho, __global float* neighbours) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const float3 pi = (float3)(x[i], y[i], z[i]);
  const float3 vi = (float3)(vx[i], vy[i], vz[i]);
  const float rhoi = rho[i];
  const float pres_i = tait_pressure(rhoi);
  const float pi_over_rho2 = pres_i / (rhoi * rhoi);
  const float eta2 = 0.01f * SPH_H * SPH_H;
  const float diffusion = 2.0f * SPH_DELTA * SPH_H * SPH_C0;
  const float support2 = 4.0f * SPH_H * SPH_H;
  const float hydrostatic_gradient = SPH_RHO0 * SPH_GRAVITY / (SPH_C0 * SPH_C0);  // kg/m⁴

  float3 acc = (float3)(0.0f, 0.0f, 0.0f);
  float drho_i = 0.0f;
  int count = 0;
  NEIGHBOUR_LOOP_BEGIN(pi, grid, cell_start, cell_end)
  const float3 xij = pi - (float3)(x[j], y[j], z[j]);
  const float r2 = dot(xij, xij);
  if (r2 < support2 && j != i) {
    const float r = sqrt(r2);
    const float f = wendland_grad_factor(r);
    ++count;
    const float3 vij = vi - (float3)(vx[j], vy[j], vz[j]);
    const float rhoj = rho[j];
    const float vdotx = dot(vij, xij);
    // δ-SPH diffuses only the dynamic part of the density difference: the hydrostatic part
    // ρ0 g (y_j − y_i)/c0² is subtracted (Fourtakas et al. 2019), so a fluid at rest stays at rest
    // near the free surface and the walls, where the kernel is truncated.
    const float rho_dynamic = (rhoi - rhoj) + hydrostatic_gradient * xij.y;
    drho_i += SPH_MASS * vdotx * f + diffusion * (SPH_MASS / rhoj) * rho_dynamic * (r2 * f) / (r2 + eta2);
    float visc = 0.0f;
    if (vdotx < 0.0f) {
      const float mu = SPH_H * vdotx / (r2 + eta2);
      visc = -SPH_ALPHA_VISC * SPH_C0 * mu / (0.5f * (rhoi + rhoj));
    }
    const float pres_j = tait_pressure(rhoj);
    acc -= (SPH_MASS * (pi_over_rho2 + pres_j / (rhoj * rhoj) + visc) * f) * xij;
  }
  NEIGHBOUR_LOOP_END

  // The floor: the terrain's tangent plane under the particle.
  const SurfacePoint floor = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, pi.x, pi.z);
  wall_response((pi.y - floor.height) * floor.normal.y, floor.normal, vi, rhoi, pres_i, &acc, &drho_i);
#if SPH_WALLS
  wall_response(pi.x, (float3)(1.0f, 0.0f, 0.0f), vi, rhoi, pres_i, &acc, &drho_i);
  wall_response(domain_x - pi.x, (float3)(-1.0f, 0.0f, 0.0f), vi, rhoi, pres_i, &acc, &drho_i);
  wall_response(pi.z, (float3)(0.0f, 0.0f, 1.0f), vi, rhoi, pres_i, &acc, &drho_i);
  wall_response(domain_z - pi.z, (float3)(0.0f, 0.0f, -1.0f), vi, rhoi, pres_i, &acc, &drho_i);
#endif
  ax[i] = acc.x;
  ay[i] = acc.y - SPH_GRAVITY;
  az[i] = acc.z;
  drho[i] = drho_i;
  neighbours[i] = (float)count;
}
