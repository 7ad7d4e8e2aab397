// SPDX-License-Identifier: MIT
// The uniform grid of the spatial hash (cell size 2h): cell coordinates, Morton keys, and the
// 27-cell neighbour loop that every particle-interaction kernel uses.
// A particle outside the grid is clamped into the nearest boundary cell. Clamping never separates
// two particles by more than one cell that were within one cell, so no neighbour is lost; only
// the candidate count of the boundary cells grows.

#define EMPTY_CELL 0xFFFFFFFFu
#define DEAD_FLAG 0x80000000u      // in id: the particle is removed at the next sort
#define TOUCHING_FLAG 0x80000000u  // in contacts: it touched the terrain at the end of its last step

typedef struct {
  float3 origin;   // m, corner of cell (0,0,0)
  float inv_cell;  // 1/m
  int3 dims;       // cells per axis
} Grid;

inline Grid make_grid(float ox, float oy, float oz, float inv_cell, int gx, int gy, int gz) {
  Grid g;
  g.origin = (float3)(ox, oy, oz);
  g.inv_cell = inv_cell;
  g.dims = (int3)(gx, gy, gz);
  return g;
}

inline int clamp_cell(float u, int dim) {
  // A NaN or huge coordinate still gets a valid cell; the step's health check reports the NaN.
  if (!(u >= 0.0f)) return 0;
  if (u >= (float)dim) return dim - 1;
  return (int)u;
}

inline int3 cell_of(float3 p, Grid g) {
  const float3 u = (p - g.origin) * g.inv_cell;
  return (int3)(clamp_cell(u.x, g.dims.x), clamp_cell(u.y, g.dims.y), clamp_cell(u.z, g.dims.z));
}

inline uint linear_cell(int3 c, Grid g) { return (uint)(c.x + g.dims.x * (c.y + g.dims.y * c.z)); }

// Interleaves the low 10 bits of v with two zero bits between each.
inline uint spread_bits(uint v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

inline uint morton_key(int3 c) {
  return spread_bits((uint)c.x) | (spread_bits((uint)c.y) << 1) | (spread_bits((uint)c.z) << 2);
}

// Visits every particle j in the 27 cells around particle i's cell, in ascending cell order.
// Usage: NEIGHBOUR_LOOP_BEGIN(pi, grid, cell_start, cell_end) { ... uses j ... } NEIGHBOUR_LOOP_END
#define NEIGHBOUR_LOOP_BEGIN(pi, grid, cell_start, cell_end)                                  \
  {                                                                                           \
    const int3 c_i_ = cell_of(pi, grid);                                                      \
    for (int dz_ = max(c_i_.z - 1, 0); dz_ <= min(c_i_.z + 1, grid.dims.z - 1); ++dz_) {      \
      for (int dy_ = max(c_i_.y - 1, 0); dy_ <= min(c_i_.y + 1, grid.dims.y - 1); ++dy_) {    \
        for (int dx_ = max(c_i_.x - 1, 0); dx_ <= min(c_i_.x + 1, grid.dims.x - 1); ++dx_) { \
          const uint cell_ = linear_cell((int3)(dx_, dy_, dz_), grid);                        \
          const uint start_ = cell_start[cell_];                                              \
          if (start_ == EMPTY_CELL) continue;                                                 \
          const uint end_ = cell_end[cell_];                                                  \
          for (uint j = start_; j < end_; ++j) {
#define NEIGHBOUR_LOOP_END \
  }                        \
  }                        \
  }                        \
  }                        \
  }
