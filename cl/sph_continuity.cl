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
// SPH_GRAVITY, SPH_WALLS, SPH_RHO_FLOOR (sph.density_min · ρ0).

// One candidate's (or wall ghost's) terms at the midpoint separation x_ij = (dx, dy, dz) with the
// drift velocity difference v_ij·x_ij = vdotx: advection to drho, and for neighbours (ghost 0) the
// density diffusion too (ghost_drho gets a ghost's advection: scaled by θ later); its kernel to the
// Shepard sum (`others`: 0 for the particle itself, whose other terms vanish with x_ii = 0).
// Branch-free, so that the candidate loop vectorises.
inline void add_pair_continuity(float* drho, float* ghost_drho, float* shepard, float dx, float dy, float dz,
                                float vdotx, float rhoi, float rhoj, float volume_j, float others, float ghost) {
  REASSOCIATE_SUMS
  const float eta2 = 0.01f * SPH_H * SPH_H;
  const float diffusion = 2.0f * SPH_DELTA * SPH_H * SPH_C0;
  const float hydrostatic_gradient = SPH_RHO0 * SPH_GRAVITY / (SPH_C0 * SPH_C0);  // kg/m⁴
  const float r2 = dx * dx + dy * dy + dz * dz;
  const float r = sqrt(r2);
  const float f = wendland_grad_factor(r);
  const float rho_dynamic = (rhoi - rhoj) + hydrostatic_gradient * dy;
  const float advection = SPH_MASS * vdotx * f;
  *drho += (1.0f - ghost) * (advection + diffusion * volume_j * rho_dynamic * (r2 * f) / (r2 + eta2));
  *ghost_drho += ghost * advection;
  *shepard += others * volume_j * wendland_w(r);
}

// The terrain under the particle (the mirrored normal velocity) and the tank walls, scaled by θ,
// added to the neighbours' sums: particle i's dρ/dt and ρ(n+1).
ALWAYS_INLINE void finish_continuity(uint i, float3 mid_i, float3 vi, float rhoi, float drho_i, float drho_ghosts,
                              float shepard, float dt, const __global float* terrain_height,
                              const __global float* terrain_normal, int tnx, int tny, float tcell,
                              __global float* drho, __global float* rho_new) {
  const SurfacePoint floor = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, mid_i.x, mid_i.z);
  const float d = (mid_i.y - floor.height) * floor.normal.y;
  const float theta = fluid_fullness(shepard, d, rhoi);
  drho_i += theta * (drho_ghosts - 2.0f * rhoi * dot(vi, floor.normal) * wall_integral(d));
  drho[i] = drho_i;
  // The floor: a particle of a thinning film or of spray only ever expands under continuity (the
  // pressure is clamped at zero below ρ0, so nothing pulls it back); held here, it does not drift
  // without bound in a long run (docs/sph.md "Failure handling").
  rho_new[i] = fmax(rhoi + dt * drho_i, SPH_RHO_FLOOR);
}

// One work-group per tile (spatial_hash.cl), as in sph_forces.cl: the tile's particles share their
// cell's candidates and their images across the tank walls within reach.
// The fields the candidates are copied from are `restrict`: only read here, and so the compiler
// may widen the copy without checking them against the local arrays.
__kernel void sph_continuity(
    const __global float* x, const __global float* y, const __global float* z,
    const __global float* restrict mid_x, const __global float* restrict mid_y, const __global float* restrict mid_z,
    const __global float* restrict drift_vx, const __global float* restrict drift_vy,
    const __global float* restrict drift_vz, const __global float* restrict volume, const __global float* restrict rho,
    const float dt, const float ox, const float oy, const float oz, const float inv_cell,
    const int gx, const int gy, const int gz, const __global uint* cell_start, const __global uint* cell_end,
    const __global uint* tile_first, const uint tile_offset, const __global float* terrain_height,
    const __global float* terrain_normal,
    const int tnx, const int tny, const float tcell, const float domain_x, const float domain_z,
    __global float* drho, __global float* rho_new) {
  // The candidates' fields in one local array: the compiler then knows they do not overlap, and
  // the copy of a row vectorises (with separate arrays it needed run-time overlap checks, which
  // failed on PoCL and sent every row through the scalar loop).
  __local float cand[9][SPH_CHUNK];
  __local float* const cx = cand[0];  // midpoints
  __local float* const cy = cand[1];
  __local float* const cz = cand[2];
  __local float* const cvx = cand[3];
  __local float* const cvy = cand[4];
  __local float* const cvz = cand[5];
  __local float* const crho = cand[6];
  __local float* const cvol = cand[7];
  __local float* const cghost = cand[8];
  __local uint cj[SPH_CHUNK];
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const TileItem t = tile_item(tile_first, tile_offset, x, y, z, grid, cell_end);  // x(n): the sort's cells
  const uint i = t.i;
  const float3 vi = (float3)(drift_vx[i], drift_vy[i], drift_vz[i]);
  const float3 mid_i = (float3)(mid_x[i], mid_y[i], mid_z[i]);
  const float rhoi = rho[i];

  __local Neighbourhood nb;
  __local Images images;
  find_tile_candidates(t, grid, cell_start, cell_end, domain_x, domain_z, &nb, &images);
  float drho_i = 0.0f, drho_ghosts = 0.0f, shepard = 0.0f;  // shepard: Σ_{j≠i} V_j W_ij, ghosts included
  const uint total = nb.total * images.count;
  for (uint base = 0; base < total; base += SPH_CHUNK) {
    TILE_ROWS_BEGIN(nb, images, base, t)
    if (image_ == 0) {
      for (uint k = first_slot_; k < end_slot_; ++k) {
        cx[k] = mid_x[k + j0_];
        cy[k] = mid_y[k + j0_];
        cz[k] = mid_z[k + j0_];
        cvx[k] = drift_vx[k + j0_];
        cvy[k] = drift_vy[k + j0_];
        cvz[k] = drift_vz[k + j0_];
        crho[k] = rho[k + j0_];
        cvol[k] = volume[k + j0_];
        cghost[k] = 0.0f;
        cj[k] = k + j0_;
      }
    } else {
      for (uint k = first_slot_; k < end_slot_; ++k) {
        const uint j = k + j0_;
        const float3 mid = image_position(image_, (float3)(mid_x[j], mid_y[j], mid_z[j]), domain_x, domain_z);
        const float3 v = image_velocity(image_, (float3)(drift_vx[j], drift_vy[j], drift_vz[j]));
        cx[k] = mid.x;
        cy[k] = mid.y;
        cz[k] = mid.z;
        cvx[k] = v.x;
        cvy[k] = v.y;
        cvz[k] = v.z;
        crho[k] = rho[j];
        cvol[k] = volume[j];
        cghost[k] = 1.0f;
        cj[k] = EMPTY_CELL;
      }
    }
    TILE_ROWS_END
    const uint length = chunk_length(total, base);
    for (uint k = chunk_candidates(total, base) + t.lane; k < length; k += t.size) {  // padding
      cx[k] = cy[k] = cz[k] = FAR_AWAY;
      cvx[k] = cvy[k] = cvz[k] = cghost[k] = 0.0f;
      crho[k] = SPH_RHO0;
      cvol[k] = SPH_MASS / SPH_RHO0;
      cj[k] = EMPTY_CELL;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    if (t.active) {
      // The chunk's own sums live in registers (what lives across a barrier lives in memory).
      float chunk_drho = 0.0f, chunk_ghosts = 0.0f, chunk_shepard = 0.0f;
      for (uint k = 0; k < length; ++k) {
        const float dx = mid_i.x - cx[k], dy = mid_i.y - cy[k], dz = mid_i.z - cz[k];
        const float vdotx = (vi.x - cvx[k]) * dx + (vi.y - cvy[k]) * dy + (vi.z - cvz[k]) * dz;
        add_pair_continuity(&chunk_drho, &chunk_ghosts, &chunk_shepard, dx, dy, dz, vdotx, rhoi, crho[k], cvol[k],
                            cj[k] != i ? 1.0f : 0.0f, cghost[k]);
      }
      drho_i += chunk_drho;
      drho_ghosts += chunk_ghosts;
      shepard += chunk_shepard;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (!t.active) return;
  finish_continuity(i, mid_i, vi, rhoi, drho_i, drho_ghosts, shepard, dt, terrain_height, terrain_normal, tnx, tny,
                    tcell, drho, rho_new);
}

// The same pass for lone tiles (sph_boundary.cl), one work-item a tile, as sph_forces_direct.
__kernel void sph_continuity_direct(
    const __global float* x, const __global float* y, const __global float* z, const __global float* mid_x,
    const __global float* mid_y, const __global float* mid_z, const __global float* drift_vx,
    const __global float* drift_vy, const __global float* drift_vz, const __global float* volume,
    const __global float* rho, const float dt, const float ox, const float oy, const float oz, const float inv_cell,
    const int gx, const int gy, const int gz, const __global uint* cell_start, const __global uint* cell_end,
    const __global uint* tile_first, const uint tile_offset, const uint tiles, const uint tile,
    const __global float* terrain_height, const __global float* terrain_normal, const int tnx, const int tny,
    const float tcell, const float domain_x, const float domain_z, __global float* drho, __global float* rho_new) {
  if (get_global_id(0) >= tiles) return;
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const LoneTile t =  // x(n): the sort's cells
      lone_tile(tile_first, tile_offset, tile, x, y, z, grid, cell_start, cell_end, domain_x, domain_z);
  for (uint i = t.first; i < t.last; ++i) {
    const float3 vi = (float3)(drift_vx[i], drift_vy[i], drift_vz[i]);
    const float3 mid_i = (float3)(mid_x[i], mid_y[i], mid_z[i]);
    const float rhoi = rho[i];
    float drho_i = 0.0f, drho_ghosts = 0.0f, shepard = 0.0f;
    LONE_CANDIDATES_BEGIN(t)
    const float3 mid = image_position(image_, (float3)(mid_x[j], mid_y[j], mid_z[j]), domain_x, domain_z);
    const float dx = mid_i.x - mid.x, dy = mid_i.y - mid.y, dz = mid_i.z - mid.z;
    SKIP_BEYOND_SUPPORT(dx * dx + dy * dy + dz * dz)
    const float3 v = image_velocity(image_, (float3)(drift_vx[j], drift_vy[j], drift_vz[j]));
    const float vdotx = (vi.x - v.x) * dx + (vi.y - v.y) * dy + (vi.z - v.z) * dz;
    add_pair_continuity(&drho_i, &drho_ghosts, &shepard, dx, dy, dz, vdotx, rhoi, rho[j], volume[j],
                        image_ != 0 || j != i ? 1.0f : 0.0f, image_ != 0 ? 1.0f : 0.0f);
    LONE_CANDIDATES_END
    finish_continuity(i, mid_i, vi, rhoi, drho_i, drho_ghosts, shepard, dt, terrain_height, terrain_normal, tnx, tny,
                      tcell, drho, rho_new);
  }
}
