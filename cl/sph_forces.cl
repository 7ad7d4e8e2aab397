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

// The sums a particle's neighbours and their wall ghosts make: the neighbours' acceleration (a),
// the ghosts' (w, scaled by θ later), the pressure-gradient sum gp = Σ_j V_j (p_j − p_i) ∇_iW_ij
// (g) and the Shepard sum of the others, ghosts included. Scalars, not float3: the vectoriser
// widens scalar code only.
typedef struct {
  float ax, ay, az, wx, wy, wz, gx, gy, gz, shepard;
} ForceSums;

inline void add_force_sums(ForceSums* to, const ForceSums* s) {
  to->ax += s->ax;
  to->ay += s->ay;
  to->az += s->az;
  to->wx += s->wx;
  to->wy += s->wy;
  to->wz += s->wz;
  to->gx += s->gx;
  to->gy += s->gy;
  to->gz += s->gz;
  to->shepard += s->shepard;
}

// What a particle contributes to its neighbours that depends on it alone, once per particle (into
// the store's spare buffers): its pressure, p/ρ² and volume m/ρ.
__kernel void forces_inputs(const __global float* rho, const uint n, __global float* pressure,
                            __global float* p_over_rho2, __global float* volume) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float r = rho[i];
  const float p = tait_pressure(r);
  pressure[i] = p;
  p_over_rho2[i] = p / (r * r);
  volume[i] = SPH_MASS / r;
}

// One candidate's contribution at x_ij = (dx, dy, dz), v_ij = (dvx, dvy, dvz): pressure and
// viscosity to the acceleration (the ghosts' own sum when `ghost` is 1), its pressure difference to
// gp, its kernel to the Shepard sum (`others`: 0 for the particle itself, whose other terms vanish
// with x_ii = 0). Branch-free, so that the candidate loop vectorises; beyond the support every
// kernel factor is 0.
inline void add_pair_force(ForceSums* s, float dx, float dy, float dz, float dvx, float dvy, float dvz, float rhoi,
                           float pres_i, float pi_over_rho2, float rhoj, float pres_j, float p_over_rho2_j,
                           float volume_j, float others, float ghost) {
  REASSOCIATE_SUMS
  const float r2 = dx * dx + dy * dy + dz * dz;
  const float r = sqrt(r2);
  const float f = wendland_grad_factor(r);
  const float vdotx = dvx * dx + dvy * dy + dvz * dz;
  const float eta2 = 0.01f * SPH_H * SPH_H;
  // Π_ij in one division; approaching pairs only.
  const float visc = -SPH_ALPHA_VISC * SPH_C0 * SPH_H * min(vdotx, 0.0f) / ((r2 + eta2) * (0.5f * (rhoi + rhoj)));
  const float a = SPH_MASS * (pi_over_rho2 + p_over_rho2_j + visc) * f;
  const float a_fluid = a * (1.0f - ghost), a_ghost = a * ghost;
  const float g = volume_j * (pres_j - pres_i) * f;
  s->ax -= a_fluid * dx;
  s->ay -= a_fluid * dy;
  s->az -= a_fluid * dz;
  s->wx -= a_ghost * dx;
  s->wy -= a_ghost * dy;
  s->wz -= a_ghost * dz;
  s->gx += g * dx;
  s->gy += g * dy;
  s->gz += g * dz;
  s->shepard += others * volume_j * wendland_w(r);
}

// The terrain under the particle and the tank walls, scaled by the fluid fullness θ, added to the
// neighbours' sums: particle i's acceleration.
ALWAYS_INLINE void finish_forces(uint i, float3 pi, float rhoi, float pres_i, const ForceSums* sum,
                          const __global float* terrain_height, const __global float* terrain_normal, int tnx,
                          int tny, float tcell, __global float* ax, __global float* ay, __global float* az) {
  const SurfacePoint floor = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, pi.x, pi.z);
  const float d = (pi.y - floor.height) * floor.normal.y;
  const float theta = fluid_fullness(sum->shepard, d, rhoi);
  const float3 gp = (float3)(sum->gx, sum->gy, sum->gz);
  const float3 acc = (float3)(sum->ax, sum->ay, sum->az) +
                     theta * ((float3)(sum->wx, sum->wy, sum->wz) + wall_force(d, floor.normal, pres_i / rhoi, gp / rhoi));
  ax[i] = acc.x;
  ay[i] = acc.y - SPH_GRAVITY;
  az[i] = acc.z;
}

// One work-group per tile (spatial_hash.cl): the tile's particles share their cell's candidates,
// and the candidates' images across the tank walls within reach.
// The fields the candidates are copied from are `restrict`: only read here, and so the compiler
// may widen the copy without checking them against the local arrays.
__kernel void sph_forces(
    const __global float* restrict x, const __global float* restrict y, const __global float* restrict z,
    const __global float* restrict vx, const __global float* restrict vy, const __global float* restrict vz,
    const __global float* restrict rho, const float ox, const float oy, const float oz, const float inv_cell,
    const int gx, const int gy, const int gz, const __global uint* cell_start, const __global uint* cell_end,
    const __global uint* tile_first, const uint tile_offset, const __global float* restrict pressure,
    const __global float* restrict p_over_rho2, const __global float* restrict volume,
    const __global float* terrain_height, const __global float* terrain_normal, const int tnx, const int tny,
    const float tcell, const float domain_x, const float domain_z, __global float* ax, __global float* ay,
    __global float* az) {
  // The candidates' fields in one local array: the compiler then knows they do not overlap, and
  // the copy of a row vectorises (with separate arrays it needed run-time overlap checks, which
  // failed on PoCL and sent every row through the scalar loop).
  __local float cand[11][SPH_CHUNK];
  __local float* const cx = cand[0];
  __local float* const cy = cand[1];
  __local float* const cz = cand[2];
  __local float* const cvx = cand[3];
  __local float* const cvy = cand[4];
  __local float* const cvz = cand[5];
  __local float* const crho = cand[6];
  __local float* const cpres = cand[7];
  __local float* const cterm = cand[8];
  __local float* const cvol = cand[9];
  __local float* const cghost = cand[10];
  __local uint cj[SPH_CHUNK];
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const TileItem t = tile_item(tile_first, tile_offset, x, y, z, grid, cell_end);
  const uint i = t.i;
  const float3 pi = (float3)(x[i], y[i], z[i]);
  const float3 vi = (float3)(vx[i], vy[i], vz[i]);
  const float rhoi = rho[i];
  const float pres_i = pressure[i];
  const float pi_over_rho2 = p_over_rho2[i];

  __local Neighbourhood nb;
  __local Images images;
  find_tile_candidates(t, grid, cell_start, cell_end, domain_x, domain_z, &nb, &images);
  ForceSums sum = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  const uint total = nb.total * images.count;
  for (uint base = 0; base < total; base += SPH_CHUNK) {
    TILE_ROWS_BEGIN(nb, images, base, t)
    if (image_ == 0) {
      for (uint k = first_slot_; k < end_slot_; ++k) {
        cx[k] = x[k + j0_];
        cy[k] = y[k + j0_];
        cz[k] = z[k + j0_];
        cvx[k] = vx[k + j0_];
        cvy[k] = vy[k + j0_];
        cvz[k] = vz[k + j0_];
        crho[k] = rho[k + j0_];
        cpres[k] = pressure[k + j0_];
        cterm[k] = p_over_rho2[k + j0_];
        cvol[k] = volume[k + j0_];
        cghost[k] = 0.0f;
        cj[k] = k + j0_;
      }
    } else {
      for (uint k = first_slot_; k < end_slot_; ++k) {
        const uint j = k + j0_;
        const float3 p = image_position(image_, (float3)(x[j], y[j], z[j]), domain_x, domain_z);
        const float3 v = image_velocity(image_, (float3)(vx[j], vy[j], vz[j]));
        cx[k] = p.x;
        cy[k] = p.y;
        cz[k] = p.z;
        cvx[k] = v.x;
        cvy[k] = v.y;
        cvz[k] = v.z;
        crho[k] = rho[j];
        cpres[k] = pressure[j];
        cterm[k] = p_over_rho2[j];
        cvol[k] = volume[j];
        cghost[k] = 1.0f;
        cj[k] = EMPTY_CELL;
      }
    }
    TILE_ROWS_END
    const uint length = chunk_length(total, base);
    for (uint k = chunk_candidates(total, base) + t.lane; k < length; k += t.size) {  // padding
      cx[k] = cy[k] = cz[k] = FAR_AWAY;
      cvx[k] = cvy[k] = cvz[k] = 0.0f;
      crho[k] = cvol[k] = SPH_RHO0;
      cpres[k] = cterm[k] = cghost[k] = 0.0f;
      cj[k] = EMPTY_CELL;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    if (t.active) {
      // The chunk's own sums live in registers (what lives across a barrier lives in memory).
      ForceSums chunk = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
      for (uint k = 0; k < length; ++k) {
        add_pair_force(&chunk, pi.x - cx[k], pi.y - cy[k], pi.z - cz[k], vi.x - cvx[k], vi.y - cvy[k],
                       vi.z - cvz[k], rhoi, pres_i, pi_over_rho2, crho[k], cpres[k], cterm[k], cvol[k],
                       cj[k] != i ? 1.0f : 0.0f, cghost[k]);
      }
      add_force_sums(&sum, &chunk);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (!t.active) return;
  finish_forces(i, pi, rhoi, pres_i, &sum, terrain_height, terrain_normal, tnx, tny, tcell, ax, ay, az);
}

// The same pass for lone tiles (sph_boundary.cl): work-item g walks tile g's neighbourhood for each
// of its particles. The sums run in another order than the tiled loop's, so its particles' results
// differ from what a tiled pass would give them in the last bits; which tiles are lone depends on
// the particles alone, so a run still has one result.
__kernel void sph_forces_direct(
    const __global float* x, const __global float* y, const __global float* z, const __global float* vx,
    const __global float* vy, const __global float* vz, const __global float* rho, const float ox, const float oy,
    const float oz, const float inv_cell, const int gx, const int gy, const int gz, const __global uint* cell_start,
    const __global uint* cell_end, const __global uint* tile_first, const uint tile_offset, const uint tiles,
    const uint tile, const __global float* pressure, const __global float* p_over_rho2, const __global float* volume,
    const __global float* terrain_height, const __global float* terrain_normal, const int tnx, const int tny,
    const float tcell, const float domain_x, const float domain_z, __global float* ax, __global float* ay,
    __global float* az) {
  if (get_global_id(0) >= tiles) return;
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const LoneTile t =
      lone_tile(tile_first, tile_offset, tile, x, y, z, grid, cell_start, cell_end, domain_x, domain_z);
  for (uint i = t.first; i < t.last; ++i) {
    const float3 pi = (float3)(x[i], y[i], z[i]);
    const float3 vi = (float3)(vx[i], vy[i], vz[i]);
    const float rhoi = rho[i];
    const float pres_i = pressure[i];
    const float pi_over_rho2 = p_over_rho2[i];
    ForceSums sum = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
    LONE_CANDIDATES_BEGIN(t)
    const float3 p = image_position(image_, (float3)(x[j], y[j], z[j]), domain_x, domain_z);
    const float dx = pi.x - p.x, dy = pi.y - p.y, dz = pi.z - p.z;
    SKIP_BEYOND_SUPPORT(dx * dx + dy * dy + dz * dz)
    const float3 v = image_velocity(image_, (float3)(vx[j], vy[j], vz[j]));
    add_pair_force(&sum, dx, dy, dz, vi.x - v.x, vi.y - v.y, vi.z - v.z, rhoi, pres_i,
                   pi_over_rho2, rho[j], pressure[j], p_over_rho2[j], volume[j],
                   image_ != 0 || j != i ? 1.0f : 0.0f, image_ != 0 ? 1.0f : 0.0f);
    LONE_CANDIDATES_END
    finish_forces(i, pi, rhoi, pres_i, &sum, terrain_height, terrain_normal, tnx, tny, tcell, ax, ay, az);
  }
}
