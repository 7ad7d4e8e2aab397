// SPDX-License-Identifier: MIT
// The fluid's boundaries, shared by the continuity (sph_continuity.cl) and momentum (sph_forces.cl)
// passes, so that the boundary terms of the two always come as a pair: whatever a wall does to the
// momentum it also does to the density, and the two exchange energy without creating any.
//
// The terrain. Under each particle the terrain's tangent plane, at distance d along its normal n,
// completes the kernel the plane truncates, semi-analytically (Ferrand et al. 2013; sph_kernel.cl):
//   momentum:   + θ (2 p_i G(d)/ρ_i) n − θ M(d)·∇p_i/ρ_i    (mirror of the particle's pressure, and
//                                                            the pressure gradient extrapolated
//                                                            into the wall, Marrone et al. 2011)
//   continuity: − θ 2 ρ_i (v_i·n) G(d)                      (the mirrored normal velocity)
// The first two terms are energy partners: their powers cancel exactly.
//
// θ, the fluid fullness. The completion assumes the particle is inside a fluid that would go on
// beyond the wall. For a raindrop, or a single sheet of water on the ground, it would be a water
// column that is not there: it compresses the drop as it nears the ground and holds it up,
// hovering about 2h above it, at a height set by where it was spawned. θ measures how much fluid
// surrounds the particle: the Shepard sum of its neighbours (without itself), S_i = Σ_j V_j W_ij,
// against the sum a particle at that distance from the wall inside a full fluid has,
// S_full(d) = 1 − Γ(d) − V_i W(0); θ = 0 up to S/S_full = 0.8 (a lone drop: 0; a single sheet of
// particles: 0.73), rising smoothly to 1 at 0.95 (two layers and more: 1.08). So drops and sheets
// feel only the Möller–Trumbore contact (integrate.cl), and water two particles deep feels the full
// wall. Both passes compute θ from their own neighbour loop.
//
// The tank walls (sph.walls, vertical planes at the domain's edges, for the validation cases) are
// free-slip mirror ghosts instead (Colagrossi & Landrini 2003): each neighbour j reflected across
// each wall within reach, and across both walls of a corner, with its density and pressure and its
// normal velocity reversed; also scaled by θ in both passes (and in the water depth).

// θ from the Shepard sum of the others and the distance to the terrain.
inline float fluid_fullness(float shepard_others, float d, float rhoi) {
  const float full = 1.0f - wall_volume(d) - (SPH_MASS / rhoi) * wendland_w(0.0f);
  const float s = clamp((shepard_others / full - 0.8f) * (1.0f / 0.15f), 0.0f, 1.0f);
  return s * s * (3.0f - 2.0f * s);
}

// The walls of a tank a particle at p is close enough to have ghosts beyond.
typedef struct {
  float domain_x, domain_z;
  bool x0, x1, z0, z1;
} TankWalls;

inline TankWalls tank_walls(float3 p, float domain_x, float domain_z) {
  const float reach = 2.0f * SPH_H;
  TankWalls w;
  w.domain_x = domain_x;
  w.domain_z = domain_z;
  w.x0 = p.x < reach;
  w.x1 = domain_x - p.x < reach;
  w.z0 = p.z < reach;
  w.z1 = domain_z - p.z < reach;
  return w;
}

// Visits the ghost images of a particle at pj moving at vj: `ghost_` its position, `ghost_v_` its
// velocity. Usage: GHOST_LOOP_BEGIN(walls, pj, vj) { ... } GHOST_LOOP_END
#define GHOST_LOOP_BEGIN(walls, pj, vj)                                                            \
  for (int wx_ = 0; wx_ < 3; ++wx_) {                                                              \
    if ((wx_ == 1 && !(walls).x0) || (wx_ == 2 && !(walls).x1)) continue;                          \
    for (int wz_ = 0; wz_ < 3; ++wz_) {                                                            \
      if ((wx_ == 0 && wz_ == 0) || (wz_ == 1 && !(walls).z0) || (wz_ == 2 && !(walls).z1)) continue; \
      const float3 ghost_ = (float3)(wx_ == 0 ? (pj).x : wx_ == 1 ? -(pj).x : 2.0f * (walls).domain_x - (pj).x, \
                                     (pj).y,                                                        \
                                     wz_ == 0 ? (pj).z : wz_ == 1 ? -(pj).z : 2.0f * (walls).domain_z - (pj).z); \
      const float3 ghost_v_ = (float3)(wx_ == 0 ? (vj).x : -(vj).x, (vj).y, wz_ == 0 ? (vj).z : -(vj).z);
#define GHOST_LOOP_END \
  }                    \
  }
