// SPDX-License-Identifier: MIT
// The incompressible solver's state at the hashed positions (DFSPH: Bender & Koschier 2015, 2017):
// each particle's summation density, the solver's factor, the fluid fullness θ, and the
// non-pressure accelerations (viscosity, gravity). In particle volumes V0 = dx³ / S, S the kernel's
// sum over a cubic lattice of spacing dx (1.0175 at h = 1.2 dx: SphSettings::lattice_sum), so that
// water at its initial spacing is at rest density rather than 1.75 % compressed:
//   ρ̂_i = ρ_i/ρ0 = V0 Σ_j W_ij + V0 Σ_ghosts W_ij' + Γ(d_i)
//   g_i  = ∇_i ρ̂_i = V0 Σ_j ∇W_ij + V0 Σ_ghosts ∇W_ij' − G(d_i) n_i
//   factor_i = 1 / (max(g_i·(g_i − G(d_i) n_i), 0) + V0² Σ_j |∇W_ij|²)
// (0 for a particle alone: nothing to solve), the inverse of the diagonal of the solves' system:
// how fast ρ̂_i changes with κ_i through a_i (dfsph_solve.cl), in which the terrain mirrors the
// particle's own pressure (its share −G n counts twice) and the neighbours' in theirs.
// The terrain under the particle is the volume map of a half-space: Γ(d) is the share of the
// kernel beyond the tangent plane at distance d (Bender et al. 2019 tabulate it for any shape; a
// plane's is closed form, sph_kernel.cl), and ∇Γ = −G(d) n. The tank walls' mirror ghosts
// (sph_boundary.cl) count like neighbours. The boundary is always complete: with a summation
// density the solves' clamp at ρ0 does what θ does for the continuity density of the weakly
// compressible passes, since a drop resting on the ground (ρ̂ = V0 W(0) + Γ(dx/2) = 0.45 at
// h = 1.2 dx) and a single sheet of water (about 0.85) stay below 1 and feel no pressure, while
// water two particles deep is completed in full. (Scaling the boundary by θ < 1 leaves the bottom
// layer's own pressure pushing it into the ground.) θ, the Shepard sum of the others against a
// full neighbourhood's (sph_boundary.cl), decides where the divergence-free solve acts.
// One work-item a particle over its cell's neighbourhood (the candidates as the direct passes walk
// them, sph_boundary.cl). Units: ρ in kg/m³, factor in m², accelerations in m/s².
// Compile-time constants (host -D): SPH_H, SPH_MASS, SPH_RHO0, SPH_C0, SPH_ALPHA_VISC, SPH_GRAVITY,
// SPH_WALLS.

#define DFSPH_V0 DFSPH_VOLUME

// Particle i's candidates: its own cell's neighbourhood and wall images, as a lone tile of one
// (through a pointer: a struct returned by value made Oclgrind 21.10 refuse the kernel, on an LLVM
// intrinsic its inlining leaves).
inline void particle_candidates(uint i, float3 pi, Grid grid, const __global uint* cell_start,
                                const __global uint* cell_end, float domain_x, float domain_z, LoneTile* t) {
  t->first = i;
  t->last = i + 1;
  const int3 cell = cell_of(pi, grid);
  t->nb = cell_neighbourhood(cell, grid, cell_start, cell_end);
  t->images = tile_images(cell, grid, domain_x, domain_z);
}

// The density pass lists each particle's neighbours within the support (and the wall ghosts', the
// image in the entry's top bits), up to DFSPH_SLOTS of them, in the order of the neighbourhood
// walk: the solves' passes then visit those few instead of every particle of 27 cells (about 400 on
// a tile of bulk water, 58 within the support). A particle with more (water squeezed together)
// walks its cells as the density pass does. The candidates left out add exactly 0 (every kernel
// factor is 0 at r² ≥ BEYOND_SUPPORT2), so both ways sum the same terms in the same order.
#define DFSPH_SLOTS 96
#define DFSPH_INDEX_MASK 0x0FFFFFFFu
#define DFSPH_IMAGE_SHIFT 28
// A listed pair is one float4, slot-major (pairs[slot·n + i]: a work-group's particles read one
// run of memory a slot): its ∇W_ij in xyz and the neighbour's entry (j, and the image in the top
// bits) in w, flipped by DFSPH_ENTRY_FLIP. The float arithmetic on the gradient carries w along in
// the vector's fourth lane, and an entry taken as a float is a denormal for every j below 2^23
// with image 0: each operation on it then takes the x86 core's microcode assist, which made the
// pressure pass five times slower. Flipped, the exponent is neither 0 nor all ones for every
// index below 125,829,120 (j's bits 23–27 are then never 15 or 16), so w is an ordinary number.
#define DFSPH_ENTRY_FLIP 0x08000000u

// Visits particle i's neighbours and ghosts (the list, or the walk when it overflowed) with j the
// sorted index, image_ the image, slot_ the list's slot (DFSPH_SLOTS on the walk) and pair_ its
// float4 (0 on the walk), as LONE_CANDIDATES_BEGIN does; the argument is the body. The kernel
// needs pi, particle i's position.
#define DFSPH_NEIGHBOURS(...)                                                                       \
  {                                                                                                \
    const uint listed_ = neighbour_count[i];                                                       \
    if (listed_ <= DFSPH_SLOTS) {                                                                  \
      for (uint slot_ = 0; slot_ < listed_; ++slot_) {                                             \
        const float4 pair_ = pairs[(size_t)slot_ * n + i];                                         \
        const uint e_ = as_uint(pair_.w) ^ DFSPH_ENTRY_FLIP;                                       \
        const uint j = e_ & DFSPH_INDEX_MASK, image_ = e_ >> DFSPH_IMAGE_SHIFT;                    \
        __VA_ARGS__                                                                                \
      }                                                                                            \
    } else {                                                                                       \
      const Grid grid_ = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);                              \
      LoneTile t_;                                                                                 \
      particle_candidates(i, pi, grid_, cell_start, cell_end, domain_x, domain_z, &t_);            \
      LONE_CANDIDATES_BEGIN(t_)                                                                    \
      if (image_ != 0 || j != i) {                                                                 \
        const uint slot_ = DFSPH_SLOTS;                                                            \
        const float4 pair_ = (float4)(0.0f);                                                       \
        __VA_ARGS__                                                                                \
      }                                                                                            \
      LONE_CANDIDATES_END                                                                          \
    }                                                                                              \
  }

// The terrain's tangent plane under a particle: distance d along the unit normal n.
typedef struct {
  float d;
  float3 n;
} FloorPlane;

inline FloorPlane floor_plane(float3 p, const __global float* terrain_height, const __global float* terrain_normal,
                              int tnx, int tny, float tcell) {
  const SurfacePoint s = terrain_surface(terrain_height, terrain_normal, tnx, tny, tcell, p.x, p.z);
  FloorPlane f;
  f.d = (p.y - s.height) * s.normal.y;
  f.n = s.normal;
  return f;
}

// The plane under particle i as the density pass stored it (one block of n per component: n, d;
// with the volume map, G(d)·n in place of n).
inline FloorPlane floor_of(uint i, uint n, const __global float* planes) {
  FloorPlane f;
  f.n = (float3)(planes[i], planes[n + i], planes[2 * n + i]);
  f.d = planes[3 * n + i];
  return f;
}

// A pair and the floor's image of its neighbour: the neighbour at pj reflected across particle
// i's tangent plane, when both lie above it (then |x_i − x_j'|² = |x_ij|² + 4 d_i d_j: an image is
// within the support only if the neighbour is). `image` is ∇_i W_ij', `w_image` W_ij' (both 0
// without an image).
typedef struct {
  float3 direct, image;
  float w, w_image;
} MirroredPair;

inline MirroredPair mirrored_pair(float3 pi, float3 pj, FloorPlane f) {
  MirroredPair m;
  const float3 xij = pi - pj;
  const float r = sqrt(dot(xij, xij));
  m.w = wendland_w(r);
  m.direct = wendland_grad_factor(r) * xij;
  const float dj = f.d - dot(xij, f.n);
  const float3 xim = xij + (2.0f * dj) * f.n;
  const float rim = sqrt(dot(xim, xim));
  const float mirrored = DFSPH_FLOOR_IMAGES && f.d > 0.0f && dj > 0.0f ? 1.0f : 0.0f;
  m.w_image = mirrored * wendland_w(rim);
  m.image = (mirrored * wendland_grad_factor(rim)) * xim;
  return m;
}

// ∇_i W_ii' of particle i and its own image across the plane (2d below it, along n).
inline float3 self_image_gradient(FloorPlane f) {
  const float d = max(f.d, 0.0f);
  return (wendland_grad_factor(2.0f * d) * 2.0f * d) * f.n;
}

// A listed pair's terms for the solves: s = ∇W_ij + ∇W_ij' (how κ_i + κ_j pushes i) and
// σ = n·∇W_ij' (the image's velocity is the neighbour's with its normal part reversed:
// (u_i − u_j)·∇W_ij + (u_i − R u_j)·∇W_ij' = (u_i − u_j)·s + 2σ u_j·n). As the density pass stored
// them for a listed neighbour, computed as it does for a particle that walks its cells. The
// solves' passes run ten times a step over the same positions: reading the pair replaces the
// gathers of x_j and the kernel's evaluations.
typedef struct {
  float3 s;
  float sigma;
} ListedPair;

inline ListedPair listed_pair(uint slot, float4 pair, const __global float* pair_image, uint i, uint n, uint j,
                              uint image, float3 pi, FloorPlane f, const __global float* x,
                              const __global float* y, const __global float* z, float domain_x,
                              float domain_z) {
  ListedPair l;
  if (slot < DFSPH_SLOTS) {
    l.s = pair.xyz;
    l.sigma = DFSPH_FLOOR_IMAGES ? pair_image[(size_t)slot * n + i] : 0.0f;
    return l;
  }
  const MirroredPair m =
      mirrored_pair(pi, image_position(image, (float3)(x[j], y[j], z[j]), domain_x, domain_z), f);
  l.s = m.direct + m.image;
  l.sigma = dot(f.n, m.image);
  return l;
}
#define DFSPH_LISTED_PAIR \
  listed_pair(slot_, pair_, pair_image, i, n, j, image_, pi, f, x, y, z, domain_x, domain_z)

__kernel void dfsph_density(const __global float* x, const __global float* y, const __global float* z, const uint n,
                            const float ox, const float oy, const float oz, const float inv_cell, const int gx,
                            const int gy, const int gz, const __global uint* cell_start,
                            const __global uint* cell_end, const __global float* terrain_height,
                            const __global float* terrain_normal, const int tnx, const int tny, const float tcell,
                            const float domain_x, const float domain_z, __global float* rho, __global float* factor,
                            __global float* theta, __global float4* pairs, __global float* pair_image,
                            __global uint* neighbour_count, __global float* planes) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const Grid grid = make_grid(ox, oy, oz, inv_cell, gx, gy, gz);
  const float3 pi = (float3)(x[i], y[i], z[i]);
  const FloorPlane terrain = floor_plane(pi, terrain_height, terrain_normal, tnx, tny, tcell);
#if DFSPH_FLOOR_IMAGES
  // The mirror plane at least the contact radius below the particle: the contact keeps a particle
  // there from the terrain's contact surface, but in a concave bend (a wall's foot) the face under
  // it can pass closer, and a particle that near its own image would count as compressed twice.
  FloorPlane f = terrain;
  f.d = max(terrain.d, SPH_CONTACT_RADIUS);
#else
  const FloorPlane f = terrain;
#endif
  LoneTile t;
  particle_candidates(i, pi, grid, cell_start, cell_end, domain_x, domain_z, &t);
  float w_fluid = 0.0f, w_ghost = 0.0f, others = 0.0f, sq_fluid = 0.0f, sq_ghost = 0.0f;
  float3 g_fluid = (float3)(0.0f), g_ghost = (float3)(0.0f), g_self = (float3)(0.0f);
  uint listed = 0;
  LONE_CANDIDATES_BEGIN(t)
  const float3 pj = image_position(image_, (float3)(x[j], y[j], z[j]), domain_x, domain_z);
  const MirroredPair m = mirrored_pair(pi, pj, f);
  const bool self = image_ == 0 && j == i;
  // The pair's push, s = ∇W_ij + ∇W_ij', and how κ_i moves neighbour j and its image, seen at i:
  // ∇W_ij + R ∇W_ij' (R the reflection). Particle i's own image is counted apart (its κ is κ_i).
  const float sigma = dot(f.n, m.image);
  const float3 s = self ? m.direct : m.direct + m.image;
  const float3 back = s - (2.0f * sigma) * f.n;
  const float sq = self ? 0.0f : dot(back, back);
  if (self) g_self = m.image;
  const float3 xij = pi - pj;
  if (dot(xij, xij) < BEYOND_SUPPORT2 && !self) {
    if (listed < DFSPH_SLOTS) {
      const uint entry = j | (image_ << DFSPH_IMAGE_SHIFT);
      pairs[(size_t)listed * n + i] = (float4)(s, as_float(entry ^ DFSPH_ENTRY_FLIP));
#if DFSPH_FLOOR_IMAGES
      pair_image[(size_t)listed * n + i] = sigma;
#endif
    }
    ++listed;
  }
  if (image_ == 0) {
    w_fluid += m.w + m.w_image;
    g_fluid += s;
    sq_fluid += sq;
    if (!self) others += m.w;
  } else {
    w_ghost += m.w + m.w_image;
    g_ghost += s;
    sq_ghost += sq;
    others += m.w;
  }
  LONE_CANDIDATES_END
  const float th = fluid_fullness((SPH_MASS / SPH_RHO0) * others, terrain.d, SPH_RHO0);
#if DFSPH_FLOOR_IMAGES
  // κ_i pushes i from every pair and twice from its own image (which carries κ_i too).
  const float rho_hat = DFSPH_V0 * (w_fluid + w_ghost);
  const float3 g = DFSPH_V0 * (g_fluid + g_ghost + 2.0f * g_self);
  const float denominator = dot(g, g) + DFSPH_V0 * DFSPH_V0 * (sq_fluid + sq_ghost);
#else
  const float rho_hat = DFSPH_V0 * (w_fluid + w_ghost) + wall_volume(f.d);
  const float3 g = DFSPH_V0 * (g_fluid + g_ghost) - wall_integral(f.d) * f.n;
  const float3 g_pressure = g - wall_integral(f.d) * f.n;  // how κ_i moves i: the terrain mirrors it
  const float denominator = max(dot(g, g_pressure), 0.0f) + DFSPH_V0 * DFSPH_V0 * (sq_fluid + sq_ghost);
#endif
  neighbour_count[i] = listed;
  // The solves read the plane (n, d); with the volume map they need only G(d)·n, stored in n's place.
#if DFSPH_FLOOR_IMAGES
  const float3 stored = f.n;
#else
  const float3 stored = wall_integral(f.d) * f.n;  // ∇Γ = −G n
#endif
  planes[i] = stored.x;
  planes[n + i] = stored.y;
  planes[2 * n + i] = stored.z;
  planes[3 * n + i] = f.d;
  rho[i] = SPH_RHO0 * rho_hat;
  factor[i] = denominator > 1e-6f / (SPH_H * SPH_H) ? 1.0f / denominator : 0.0f;
  theta[i] = th;
}

// Viscosity, gravity and the floor images' hydrostatic pressure at the divergence-free velocities.
// Viscosity: Monaghan's artificial viscosity with the weakly compressible solver's α and c0
// (kinematic viscosity α c0 h / 10), on the rest density, as an explicit force; the wall ghosts'
// too (free slip: their tangential velocity is the particle's own, so they damp only the normal
// motion).
//   dv_i/dt = −Σ_j m Π_ij ∇_iW_ij + g − V0 Σ_j' c_j ∇W_ij',  Π_ij = −α c0 μ_ij / ρ0 when
//   v_ij·x_ij < 0, μ_ij = h v_ij·x_ij / (|x_ij|² + 0.01h²)
// The floor's image j' of a neighbour lies 2 d_j below it along the normal; its pressure is the
// neighbour's κ_j (in the solves) plus the hydrostatic increment c_j = 2 g d_j n_y (Adami et al.
// 2012: the pressure carried on across the wall), which does not depend on κ and so is a force
// here. Without it the image layer mirrors the bottom layer's pressure and holds it with half the
// bulk's pressure gradient.
__kernel void dfsph_non_pressure(const __global float* x, const __global float* y, const __global float* z,
                                 const __global float* vx, const __global float* vy, const __global float* vz,
                                 const uint n, const float ox, const float oy,
                                 const float oz, const float inv_cell, const int gx, const int gy, const int gz,
                                 const __global uint* cell_start, const __global uint* cell_end,
                                 const float domain_x, const float domain_z, const __global float4* pairs,
                                 const __global uint* neighbour_count, const __global float* planes,
                                 const __global float* theta, __global float* ax, __global float* ay, __global float* az) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float3 pi = (float3)(x[i], y[i], z[i]);
  const float3 vi = (float3)(vx[i], vy[i], vz[i]);
  const FloorPlane f = floor_of(i, n, planes);
  const float eta2 = 0.01f * SPH_H * SPH_H;
  const float lift = 2.0f * SPH_GRAVITY * f.n.y * theta[i];  // c_j per metre of d_j
#if DFSPH_FLOOR_IMAGES
  float3 acc = (-DFSPH_V0 * lift * max(f.d, 0.0f)) * self_image_gradient(f);
#else
  float3 acc = (float3)(0.0f);
#endif
  DFSPH_NEIGHBOURS(
    const float3 pj = image_position(image_, (float3)(x[j], y[j], z[j]), domain_x, domain_z);
    const float3 vj = image_velocity(image_, (float3)(vx[j], vy[j], vz[j]));
    const float3 xij = pi - pj;
    const float r2 = dot(xij, xij);
    const float vdotx = dot(vi - vj, xij);
    const float visc = -SPH_ALPHA_VISC * SPH_C0 * SPH_H * min(vdotx, 0.0f) / ((r2 + eta2) * SPH_RHO0);
    acc += (-SPH_MASS * visc * wendland_grad_factor(sqrt(r2))) * xij;
    if (DFSPH_FLOOR_IMAGES) {
      const MirroredPair m = mirrored_pair(pi, pj, f);
      acc += (-DFSPH_V0 * lift * max(f.d - dot(xij, f.n), 0.0f)) * m.image;
    }
  )
  ax[i] = acc.x;
  ay[i] = acc.y - SPH_GRAVITY;
  az[i] = acc.z;
}
