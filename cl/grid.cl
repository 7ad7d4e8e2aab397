// SPDX-License-Identifier: MIT
// The uniform grid of the spatial hash (cell size 2h): cell coordinates, the linear cell index (the
// sort key), and the 27-cell neighbour loop that every particle-interaction kernel uses.
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

// Visits every particle j in the 27 cells around particle i's cell as 9 rows along x. The sort key
// is the linear cell index (x fastest), so the up to three cells of a row hold one contiguous range
// of sorted particles: from the first occupied cell's start to the last one's end. The order of the
// visit is ascending cell, then ascending j. (The hot neighbour passes are tiled instead, below.)
// Usage: NEIGHBOUR_ROWS_BEGIN(pi, grid, cell_start, cell_end) { ... uses j ... } NEIGHBOUR_ROWS_END
#define NEIGHBOUR_ROWS_BEGIN(pi, grid, cell_start, cell_end)                                   \
  {                                                                                           \
    const int3 c_i_ = cell_of(pi, grid);                                                      \
    const int x0_ = max(c_i_.x - 1, 0), x1_ = min(c_i_.x + 1, grid.dims.x - 1);               \
    for (int dz_ = max(c_i_.z - 1, 0); dz_ <= min(c_i_.z + 1, grid.dims.z - 1); ++dz_) {      \
      for (int dy_ = max(c_i_.y - 1, 0); dy_ <= min(c_i_.y + 1, grid.dims.y - 1); ++dy_) {    \
        const uint row_ = linear_cell((int3)(0, dy_, dz_), grid);                             \
        uint begin_ = EMPTY_CELL, end_ = 0;                                                   \
        for (int cx_ = x0_; cx_ <= x1_; ++cx_) {                                              \
          const uint s_ = cell_start[row_ + cx_];                                             \
          if (s_ == EMPTY_CELL) continue;                                                     \
          if (begin_ == EMPTY_CELL) begin_ = s_;                                              \
          end_ = cell_end[row_ + cx_];                                                        \
        }                                                                                     \
        if (begin_ == EMPTY_CELL) continue;                                                   \
        for (uint j = begin_; j < end_; ++j) {
#define NEIGHBOUR_ROWS_END \
  }                        \
  }                        \
  }                        \
  }

// The 27-cell neighbourhood of one cell as its 9 rows' runs of sorted particles, numbered as one
// sequence 0 .. total−1 in the order NEIGHBOUR_ROWS visits them. A tile's work-items all compute
// the same one (it depends on the cell only) and share its candidates through local memory.
typedef struct {
  uint begin[9], count[9];
  uint start[9];  // the row's first candidate in the sequence
  uint rows, total;
} Neighbourhood;

inline Neighbourhood cell_neighbourhood(int3 c, Grid grid, const __global uint* cell_start,
                                        const __global uint* cell_end) {
  Neighbourhood nb;
  nb.total = 0;
  int rows = 0;
  const int x0 = max(c.x - 1, 0), x1 = min(c.x + 1, grid.dims.x - 1);
  for (int dz = max(c.z - 1, 0); dz <= min(c.z + 1, grid.dims.z - 1); ++dz) {
    for (int dy = max(c.y - 1, 0); dy <= min(c.y + 1, grid.dims.y - 1); ++dy) {
      const uint row = linear_cell((int3)(0, dy, dz), grid);
      uint begin = EMPTY_CELL, end = 0;
      for (int cx = x0; cx <= x1; ++cx) {
        const uint s = cell_start[row + cx];
        if (s == EMPTY_CELL) continue;
        if (begin == EMPTY_CELL) begin = s;
        end = cell_end[row + cx];
      }
      if (begin == EMPTY_CELL) continue;
      nb.begin[rows] = begin;
      nb.count[rows] = end - begin;
      nb.start[rows] = nb.total;
      nb.total += end - begin;
      ++rows;
    }
  }
  nb.rows = rows;
  return nb;
}
