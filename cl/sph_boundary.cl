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
// normal velocity reversed; also scaled by θ in both passes (and in the water depth). The ghosts
// are extra candidates of the tiled neighbour loops (tile_images), so they vectorise too.

// θ from the Shepard sum of the others and the distance to the terrain.
inline float fluid_fullness(float shepard_others, float d, float rhoi) {
  const float full = 1.0f - wall_volume(d) - (SPH_MASS / rhoi) * wendland_w(0.0f);
  const float s = clamp((shepard_others / full - 0.8f) * (1.0f / 0.15f), 0.0f, 1.0f);
  return s * s * (3.0f - 2.0f * s);
}

// The images a tile's candidates are seen as: image m = wx + 3 wz, with wx, wz = 0 (none), 1 (across
// the wall at 0), 2 (across the far wall at domain_x or domain_z), both for a corner; image 0 is
// the candidate itself. A wall's images are taken when it lies within 2h of the tile's cell; an
// image too far from a particle adds exactly 0 (every kernel factor is 0 beyond the support), so
// taking them per cell rather than per particle changes nothing but the work.
typedef struct {
  uint count;
  uint image[9];
} Images;

inline Images tile_images(int3 cell, Grid grid, float domain_x, float domain_z) {
  Images im;
  im.count = 1;
  im.image[0] = 0;
#if SPH_WALLS
  // A particle beyond 2h of a wall sees no image (both it and the neighbour are on the fluid's
  // side, so the image is farther than the wall's distance and the neighbour's together). A cell
  // whose near side is 2h from the wall qualifies only through rounding: left out.
  const float size = 1.0f / grid.inv_cell;
  const float reach = 2.0f * SPH_H - 1e-4f * size;
  const float x_lo = grid.origin.x + cell.x * size, z_lo = grid.origin.z + cell.z * size;
  const bool near_x[3] = {true, x_lo < reach, domain_x - (x_lo + size) < reach};
  const bool near_z[3] = {true, z_lo < reach, domain_z - (z_lo + size) < reach};
  for (uint m = 1; m < 9; ++m) {
    if (near_x[m % 3] && near_z[m / 3]) im.image[im.count++] = m;
  }
#endif
  return im;
}

// The position and velocity of image m of a particle (free-slip: the normal velocity reversed).
inline float3 image_position(uint m, float3 p, float domain_x, float domain_z) {
  const uint wx = m % 3, wz = m / 3;
  return (float3)(wx == 0 ? p.x : wx == 1 ? -p.x : 2.0f * domain_x - p.x, p.y,
                  wz == 0 ? p.z : wz == 1 ? -p.z : 2.0f * domain_z - p.z);
}

inline float3 image_velocity(uint m, float3 v) {
  return (float3)(m % 3 == 0 ? v.x : -v.x, v.y, m / 3 == 0 ? v.z : -v.z);
}

// Tiled neighbour passes (one work-group per tile of a cell's particles, spatial_hash.cl):
// the candidates are loaded SPH_CHUNK at a time (sized from the device's local memory by the host)
// into local memory by the whole group, then every work-item runs over the chunk. That loop reads
// contiguous local memory and its trip count is a multiple of CANDIDATE_PAD: the vectoriser widens
// it across candidates. The slots past the last candidate are a particle too far away to interact
// (every kernel factor is exactly 0 there).
#define CANDIDATE_PAD 16
#define FAR_AWAY 1.0e18f

// The real candidates in chunk `base`; the padded slots follow them.
inline uint chunk_candidates(uint total, uint base) { return min(total - base, (uint)SPH_CHUNK); }

// The candidates of chunk `base` that the loop runs over: the real ones rounded up to CANDIDATE_PAD.
inline uint chunk_length(uint total, uint base) {
  const uint real = chunk_candidates(total, base);
  return min((real + CANDIDATE_PAD - 1) / CANDIDATE_PAD * CANDIDATE_PAD, (uint)SPH_CHUNK);
}

// A work-item's place in its tile (spatial_hash.cl): the tile's first particle and cell, the
// group's size, and the particle the work-item computes (an idle one, past the tile's end, still
// reads the first particle: every work-item must reach the barriers).
typedef struct {
  uint first, size, lane, i;
  int3 cell;
  bool active;
} TileItem;

inline TileItem tile_item(const __global uint* tile_first, uint tile_offset, const __global float* x,
                          const __global float* y, const __global float* z, Grid grid,
                          const __global uint* cell_end) {
  TileItem t;
  t.first = tile_first[tile_offset + get_group_id(0)];
  t.size = get_local_size(0);
  t.cell = cell_of((float3)(x[t.first], y[t.first], z[t.first]), grid);
  const uint last = min(t.first + t.size, cell_end[linear_cell(t.cell, grid)]);
  t.lane = get_local_id(0);
  t.active = t.first + t.lane < last;
  t.i = t.active ? t.first + t.lane : t.first;
  return t;
}

// The tile's neighbourhood and wall images, found once by its first work-item for the group.
inline void find_tile_candidates(TileItem t, Grid grid, const __global uint* cell_start,
                                 const __global uint* cell_end, float domain_x, float domain_z,
                                 __local Neighbourhood* nb, __local Images* images) {
  if (t.lane == 0) {
    *nb = cell_neighbourhood(t.cell, grid, cell_start, cell_end);
    *images = tile_images(t.cell, grid, domain_x, domain_z);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
}

// A tile's candidate sequence is every image of every neighbourhood candidate, row by row. This
// visits the work-item's share of chunk [base, base + SPH_CHUNK) one row at a time: `image_` the
// image the row's candidates are seen as, the row's slots of the chunk [first_slot_, end_slot_)
// (empty for a row outside the chunk), and slot k holding the particle of sorted index k + j0_.
// Each work-item copies whole rows (work-item q the rows q, q + tile size, ...): a row is one
// contiguous run, and no work-item walks rows it does not copy. The copy of a row of image 0 (the
// candidates themselves: every row of a tile away from the tank walls) is then a loop between two
// contiguous ranges, which the vectoriser widens; the passes keep it apart from the copy of the wall
// images, since one loop with the image arithmetic in it (even with image 0) stays scalar.
// Usage: TILE_ROWS_BEGIN(nb, images, base, item) {...} TILE_ROWS_END, `item` the work-item's TileItem.
#define TILE_ROWS_BEGIN(nb, im, base, item)                                                        \
  for (uint q_ = (item).lane; q_ < (im).count * (nb).rows; q_ += (item).size) {                    \
    const uint image_ = (im).image[q_ / (nb).rows], r_ = q_ % (nb).rows;                         \
    const uint row_start_ = (q_ / (nb).rows) * (nb).total + (nb).start[r_];                      \
    const uint lo_ = max(row_start_, (base));                                                    \
    const uint hi_ = max(lo_, min(row_start_ + (nb).count[r_], (base) + SPH_CHUNK));            \
    const uint first_slot_ = lo_ - (base), end_slot_ = hi_ - (base);                             \
    const uint j0_ = (base) + (nb).begin[r_] - row_start_;
#define TILE_ROWS_END }

// A lone tile (spatial_hash.cl): a cell's last few particles, whose pass runs one work-item a tile
// and walks the neighbourhood directly from global memory, without the group's copies and barriers.
// The work-item's tile: its particles [first, last), its cell's neighbourhood and wall images.
typedef struct {
  uint first, last;
  Neighbourhood nb;
  Images images;
} LoneTile;

inline LoneTile lone_tile(const __global uint* tile_first, uint tile_offset, uint tile, const __global float* x,
                          const __global float* y, const __global float* z, Grid grid,
                          const __global uint* cell_start, const __global uint* cell_end, float domain_x,
                          float domain_z) {
  LoneTile t;
  // Tiles of one particle are every particle in order: the hash builds no list for them.
  t.first = tile == 1 ? tile_offset + get_global_id(0) : tile_first[tile_offset + get_global_id(0)];
  const int3 cell = cell_of((float3)(x[t.first], y[t.first], z[t.first]), grid);
  t.last = min(t.first + tile, cell_end[linear_cell(cell, grid)]);
  t.nb = cell_neighbourhood(cell, grid, cell_start, cell_end);
  t.images = tile_images(cell, grid, domain_x, domain_z);
  return t;
}

// Visits the candidates of a lone tile as the tiled passes see them: every image of every
// neighbourhood candidate, row by row; `image_` the image (0: the candidate itself), j its sorted
// index. Usage: LONE_CANDIDATES_BEGIN(lone) {...} LONE_CANDIDATES_END, `lone` a LoneTile.
// On a wide device (SPH_SKIP_FAR, host -D) the direct passes skip a candidate at r² ≥
// BEYOND_SUPPORT2 before reading the rest of its fields: about five in six are, and a GPU's
// per-particle passes then read only their positions. The bound is 2h with a margin of 1.25·10⁻⁵
// over the rounding of r and q = r/h, so every kernel factor of a skipped candidate is exactly 0.
// A CPU keeps the branch-free loop, which PoCL widens across the candidates (with the branch the
// sums run in another order: other bits).
#define BEYOND_SUPPORT2 (4.0001f * SPH_H * SPH_H)
#if SPH_SKIP_FAR
#define SKIP_BEYOND_SUPPORT(r2) \
  if ((r2) >= BEYOND_SUPPORT2) continue;  // NaN goes on, into the sums and the health check
#else
#define SKIP_BEYOND_SUPPORT(r2)
#endif
#define LONE_CANDIDATES_BEGIN(lone)                                                      \
  for (uint m_ = 0; m_ < (lone).images.count; ++m_) {                                    \
    const uint image_ = (lone).images.image[m_];                                         \
    for (uint r_ = 0; r_ < (lone).nb.rows; ++r_) {                                       \
      for (uint j = (lone).nb.begin[r_]; j < (lone).nb.begin[r_] + (lone).nb.count[r_]; ++j) {
#define LONE_CANDIDATES_END \
  }                         \
  }                         \
  }
