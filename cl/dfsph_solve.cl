// SPDX-License-Identifier: MIT
// DFSPH's two pressure solves (Bender & Koschier 2017, Algorithms 2 and 3; the Jacobi form of
// SPlisHSPlasH), on the density, factor and θ of dfsph_density.cl. Each solves for a pressure
// κ (p/ρ² · ρ0, m²/s²) whose acceleration
//   a_i = −V0 Σ_j (κ_i + κ_j) ∇W_ij − V0 Σ_ghosts (κ_i + κ_j) ∇W_ij' + 2 κ_i G(d_i) n_i
// (the terrain's volume map with the particle's own pressure mirrored, as the weakly compressible
// momentum pass has it: with κ_i alone there, the particle's own pressure cancels and its
// neighbours' pressure pushes the bottom layer into the ground, which the solve can only answer
// with a pressure that alternates from layer to layer)
// applied over the step dt removes
//   the constant-density solve:  the predicted compression, ρ̂_i + dt Δ_i(v) ≤ 1, and
//   the divergence-free solve:   the rate of compression, Δ_i(v) ≤ 0,
// where Δ_i(u) = V0 Σ_j (u_i − u_j)·∇W_ij + V0 Σ_ghosts (u_i − u_j')·∇W_ij' − G(d_i) u_i·n_i
// is the rate of change of ρ̂_i that the velocities u cause (the ghosts' u mirrored as their
// velocities are; the terrain at rest, its share the plane's exact rate). The system is not
// symmetric: the terrain pushes with 2κ_i but compresses at the rate of one. On a lattice of water
// on a floor diag⁻¹A has one eigenvalue below 0 (−0.02 to −0.05 with the particles jittered), a
// mode alternating from particle to particle along the floor that grows 1–2.5 % a Jacobi
// iteration; a solve of a few iterations leaves it small, one of hundreds (a tolerance of 0.001 %
// in a deep tank) runs away. Making the system symmetric by counting the terrain's rate twice as
// well converges on every mode, but then the solve believes the terrain's push twice as effective
// as it is: under heavy rain on ponds the water beside the ground compressed step after step to
// 1.7 ρ0. Only compression is removed: κ ≥ 0, so water may thin at a free surface and a drop
// keeps no pressure. Projected Jacobi: κ_i ← max(κ_i − ω r_i · factor_i / dt^k, 0) with the
// residual r_i = s_i − dt^k Δ_i(a) (k = 2 for the density, 1 for the divergence), s_i the source
// (IISPH's clamp; a κ that only grew, as in SPlisHSPlasH, cannot undo a warm start that pushes
// too hard). The divergence-free solve acts only where θ > 0 (a full neighbourhood, as SPlisHSPlasH
// leaves particles with fewer than 20 neighbours out): at a free surface the summation density is
// deficient and the constant-density solve alone keeps the water from compressing.
// Every particle adds its error to fixed-point sums (integers, summed in its work-group, then
// atomically: the totals do not depend on the order), from which the host decides whether to
// iterate again.
// Compile-time constants (host -D): SPH_H, SPH_MASS, SPH_RHO0, SPH_WALLS.

#define DFSPH_ERROR_QUANTUM 1e-9f  // of the dimensionless density error, in the fixed-point sums
#define DFSPH_GROUP 64             // work-items a group of dfsph_density_change (Dfsph::kGroup)
// Jacobi's relaxation, as IISPH's (Ihmsen et al. 2014). Jacobi damps a mode when ω λ < 2, λ its
// eigenvalue of diag⁻¹A; the largest is 3.5 on a lattice of water (its shortest pressure waves)
// and 3.7–3.9 where the particles are jittered by 0.15–0.3 dx (measured on the matrix of a small
// tank), so with the full step (1) the iteration diverges, and 0.5 is about the largest that
// damps them: 0.55 took 6 % fewer iterations in a storm.
#define DFSPH_RELAXATION 0.5f

// u = v + a·dt/2 with the non-pressure accelerations of dfsph_non_pressure: into v itself, the
// step's closing half kick (its opening one is the drift's, integrate.cl); into the spares the
// iterations later fill with the pressure acceleration, the velocity the drift will move the
// particles at without pressure, the constant-density solve's source.
__kernel void dfsph_half_kick(const __global float* vx, const __global float* vy, const __global float* vz,
                                   const __global float* ax, const __global float* ay, const __global float* az,
                                   const uint n, const float half_dt, __global float* ux, __global float* uy,
                                   __global float* uz) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  ux[i] = vx[i] + half_dt * ax[i];
  uy[i] = vy[i] + half_dt * ay[i];
  uz[i] = vz[i] + half_dt * az[i];
}

// The pressure acceleration a_i of the current κ (above), into (apx, apy, apz).
__kernel void dfsph_pressure_acceleration(
    const __global float* x, const __global float* y, const __global float* z, const __global float* kappa,
    const uint n, const float ox, const float oy, const float oz, const float inv_cell,
    const int gx, const int gy, const int gz, const __global uint* cell_start, const __global uint* cell_end,
    const float domain_x, const float domain_z, const __global float4* pairs,
    const __global float* pair_image, const __global uint* neighbour_count, const __global float* planes,
    __global float* apx, __global float* apy, __global float* apz) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float3 pi = (float3)(x[i], y[i], z[i]);
  const float ki = kappa[i];
  const FloorPlane f = floor_of(i, n, planes);
#if DFSPH_FLOOR_IMAGES
  // Its own image carries κ_i as well: twice κ_i on that pair.
  float3 acc = (-DFSPH_V0 * 2.0f * ki) * self_image_gradient(f);
#else
  float3 acc = (float3)(0.0f);
#endif
  DFSPH_NEIGHBOURS(
    acc += (-DFSPH_V0 * (ki + kappa[j])) * DFSPH_LISTED_PAIR.s;
  )
#if !DFSPH_FLOOR_IMAGES
  acc += (2.0f * ki) * f.n;  // G(d)·n, the volume map's: the particle's own κ mirrored
#endif
  apx[i] = acc.x;
  apy[i] = acc.y;
  apz[i] = acc.z;
}

// Δ_i(u) (above) for velocities or accelerations u (the divergence-free solve's source takes v, the
// constant-density solve's the drift velocity of dfsph_half_kick), then one of two updates of particle i:
//   source (iterate 0): the source s_i from u (density: 1 − ρ̂_i − dt Δ_i(u); divergence:
//     −Δ_i(u)), and κ_i's warm start, the κ the last solve ended with (kept as κ·dt^k, so that it
//     does not depend on the step): the projection lowers it again where it is too high;
//   iterate (iterate 1): u = a of the current κ; the residual and the Jacobi update of κ_i.
// `dt_k` is dt² (density) or dt (divergence); `error_scale` turns a residual into a density error
// (1, or dt for a rate). `errors` gets Σ error and the count of particles in the solve (residual
// below 0, or after an iteration pressure above 0) in quanta, `error_max` the largest error's bits.
__kernel void dfsph_density_change(
    const __global float* x, const __global float* y, const __global float* z, const __global float* ux,
    const __global float* uy, const __global float* uz, const __global float* rho, const __global float* factor,
    const __global float* theta, __global float* source, __global float* kappa, const uint n, const float ox,
    const float oy, const float oz, const float inv_cell, const int gx, const int gy, const int gz,
    const __global uint* cell_start, const __global uint* cell_end, const float domain_x,
    const float domain_z, const float dt, const float dt_k, const float error_scale, const uint divergence,
    const uint iterate, const __global float4* pairs, const __global float* pair_image,
    const __global uint* neighbour_count, const __global float* planes,
    volatile __global long* errors, volatile __global uint* error_max) {
  __local long group_quanta[DFSPH_GROUP];
  __local uint group_count[DFSPH_GROUP], group_worst[DFSPH_GROUP];
  const uint i = get_global_id(0);
  long quanta = 0;  // particle i's error in quanta, whether it is in the solve, the error's bits
  uint counted = 0, worst = 0;
  if (i < n) {
  const float3 pi = (float3)(x[i], y[i], z[i]);
  const float3 ui = (float3)(ux[i], uy[i], uz[i]);
  const FloorPlane f = floor_of(i, n, planes);
#if DFSPH_FLOOR_IMAGES
  // Its own image moves with its normal velocity reversed: (u_i − R u_i)·∇W_ii' = 2 (u_i·n) n·∇W_ii'.
  float sum = 2.0f * dot(ui, f.n) * dot(f.n, self_image_gradient(f));
  DFSPH_NEIGHBOURS(
    const float3 uj = image_velocity(image_, (float3)(ux[j], uy[j], uz[j]));
    const ListedPair l = DFSPH_LISTED_PAIR;
    sum += dot(ui - uj, l.s) + 2.0f * l.sigma * dot(uj, f.n);
  )
  const float change = DFSPH_V0 * sum;
#else
  float sum = 0.0f;
  DFSPH_NEIGHBOURS(
    const float3 uj = image_velocity(image_, (float3)(ux[j], uy[j], uz[j]));
    sum += dot(ui - uj, DFSPH_LISTED_PAIR.s);
  )
  const float change = DFSPH_V0 * sum - dot(ui, f.n);  // G(d)·n: the terrain at rest
#endif
  // The divergence-free solve leaves particles of a deficient neighbourhood alone.
  const bool solved = !divergence || theta[i] > 0.0f;
  float residual;
  float ki = kappa[i];
  if (!iterate) {
    const float s = !solved ? 0.0f : divergence ? -change : 1.0f - rho[i] * (1.0f / SPH_RHO0) - dt * change;
    source[i] = s;
    residual = min(s, 0.0f);
    ki = solved ? ki / dt_k : 0.0f;
  } else {
    // Projected Jacobi: κ may fall again (a warm start or an iteration that pushed too hard) but
    // never below 0; the error is the residual where there is pressure, the compression elsewhere.
    const float r = solved ? source[i] - dt_k * change : 0.0f;
    ki = max(ki - DFSPH_RELAXATION * r * factor[i] / dt_k, 0.0f);
    residual = ki > 0.0f ? -fabs(r) : min(r, 0.0f);
  }
  kappa[i] = ki;
  if (residual < 0.0f || (iterate && ki > 0.0f)) {
    const float e = residual < 0.0f ? -residual * error_scale : 0.0f;
    quanta = (long)(e * (1.0f / DFSPH_ERROR_QUANTUM) + 0.5f);
    counted = 1;
    worst = as_uint(e);
  }
  }
  // The work-group's sums in local memory, then one atomic each: on a CPU, atomics on one address
  // from every particle serialise the cores. Integers and a maximum: the totals do not depend on
  // the order.
  const uint l = get_local_id(0);
  group_quanta[l] = quanta;
  group_count[l] = counted;
  group_worst[l] = worst;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint reach = DFSPH_GROUP / 2; reach > 0; reach >>= 1) {
    if (l < reach) {
      group_quanta[l] += group_quanta[l + reach];
      group_count[l] += group_count[l + reach];
      group_worst[l] = max(group_worst[l], group_worst[l + reach]);
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (l == 0 && group_count[0] > 0) {
    atom_add(&errors[0], group_quanta[0]);
    atom_add(&errors[1], (long)group_count[0]);
    atomic_max(error_max, group_worst[0]);
  }
}

// The end of a solve: v += dt·a of the last iteration's κ (the one whose residual ended the
// solve), and κ kept as κ·dt^k for the next step's warm start.
__kernel void dfsph_finish(__global float* vx, __global float* vy, __global float* vz, const __global float* apx,
                           const __global float* apy, const __global float* apz, __global float* kappa,
                           const uint n, const float dt, const float dt_k) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  vx[i] += dt * apx[i];
  vy[i] += dt * apy[i];
  vz[i] += dt * apz[i];
  kappa[i] *= dt_k;
}
