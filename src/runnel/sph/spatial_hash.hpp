// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "runnel/compute/context.hpp"
#include "runnel/compute/kernel.hpp"
#include "runnel/sph/particle_store.hpp"

namespace runnel {

// A uniform grid over an axis-aligned box. Particles outside are clamped into the boundary cells.
struct GridSpec {
  float origin[3] = {0, 0, 0};  // m
  float cell = 1.0f;            // m (2h for SPH)
  int dims[3] = {1, 1, 1};

  // The grid of cell size `cell` covering [lo, hi]; throws if a side needs more than 1024 cells.
  static GridSpec covering(const double lo[3], const double hi[3], double cell);
  std::size_t cell_count() const { return static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]; }
  int key_bits() const;  // bits of a linear cell key, the dead key (cell_count()) included
};

// Host side of cl/spatial_hash.cl: sorts particles by the linear index of their cell with a
// deterministic stable radix sort, gathers every persistent field into that order, drops dead
// particles, and builds the cell start/end tables that the neighbour loops read. Owns no particle
// data (CompactNSearch's lesson): it only computes an order and cell ranges for the store.
class SpatialHash {
 public:
  // tile: the most particles of one cell a neighbour pass's work-group takes (its size); 0 for the
  // device's own (device_tile()).
  SpatialHash(ComputeContext& compute, const GridSpec& grid, std::uint32_t tile = 0);

  // The neighbour passes' tile on this device. A CPU: kDefaultTile, a cell's particles sharing the
  // candidates they copy into local memory, so that its vector lanes run over them. A wide device
  // (a GPU): 1, so that every particle is a lone tile and the direct kernels give each its own
  // work-item reading its neighbours from global memory, as GPU SPH codes do (DualSPHysics): the
  // device's caches share the candidates among neighbouring work-items, and it has work-items for
  // every particle instead of idle lanes in groups of a cell's 8 to 27.
  static std::uint32_t device_tile(const ComputeContext& compute);

  // Sorts and reorders `store` in place; afterwards store.size() counts live particles only.
  void build(ParticleStore& store);
  // The build in two halves, for a caller with work to queue that needs neither the live count nor
  // the tiles: begin_build() queues the sort, the tables and the read of their summary;
  // finish_build() waits for that read (the device meanwhile runs what was queued after it) and
  // truncates the store to the live particles. In between, the store still counts the dead ones,
  // sorted to its end with their id's DEAD_FLAG, and the tile counts are the last build's.
  void begin_build(ParticleStore& store);
  void finish_build(ParticleStore& store);
  // Whether the sort also carries each particle's water depth (a rate field, otherwise measured
  // again after every sort): for a solver that measures it only every so often.
  void carry_water_depth(bool on) { carry_depth_ = on; }
  // The sort gathers these rate fields too: the state a pressure solver keeps between steps.
  void carry_fields(std::vector<ParticleField> fields) { carried_fields_ = std::move(fields); }

  const GridSpec& grid() const { return grid_; }
  const cl::Buffer& cell_start() const { return cell_start_; }
  const cl::Buffer& cell_end() const { return cell_end_; }
  // The radix sort: as few passes over the keys' bits as digits of at most kMaxDigitBits (in
  // runs, a CPU's) or kMaxTileDigitBits (in tiles, a GPU's) allow, the bits shared evenly (18-bit
  // keys: two passes of 9). Each pass is three launches (histogram, scan, scatter); a wider digit
  // costs a longer histogram a chunk or tile. A tile's counts (one a digit, for 1,024 keys) go in
  // a spare buffer of the store: 512 · ⌈n / 1,024⌉ fit from n = 1,024 on, 1,024 · ⌈n / 1,024⌉ not.
  static constexpr int kMaxDigitBits = 10, kMaxTileDigitBits = 9;
  int radix_passes() const { return passes_; }
  int radix_digit_bits() const { return digit_bits_; }
  cl_uint radix() const { return cl_uint{1} << digit_bits_; }  // a digit's values
  // Each occupied cell's particles in tiles of at most tile_size(), in sorted order, those of more
  // than kSmallTile particles first, then those of more than kLoneTile, then the rest:
  // tile_first()[t] is the sorted index of tile t's first particle; the tile size and its cell's
  // cell_end bound it. With a tile of 1 every particle is a lone tile and the list, the identity,
  // is not built (tile_first() then holds nothing of use).
  std::uint32_t tile_size() const { return tile_; }
  // Sets the tile size (from the next build on). Tests run a device's passes as another would.
  void set_tile(std::uint32_t tile) { tile_ = tile; }
  std::uint32_t tile_count() const { return tiles_ + small_tiles_ + lone_tiles_; }
  std::uint32_t small_tile_count() const { return small_tiles_; }
  std::uint32_t lone_tile_count() const { return lone_tiles_; }
  // The most particles a lone tile holds, kLoneTile unless set (from the next build on). Tests set
  // the tile size, so that every tile takes the direct kernels.
  void set_lone_tile(std::uint32_t most) { lone_ = most; }
  const cl::Buffer& tile_first() const { return tile_first_; }
  // The grid arguments every kernel that hashes a position takes: ox, oy, oz, inv_cell, gx, gy, gz.
  void bind_grid(Kernel& kernel) const;
  // The grid and its cell ranges (cell_start, cell_end): what a neighbour loop walks.
  void bind_cells(Kernel& kernel) const;
  // Binds the cell ranges and the tile list to a neighbour pass's two kernels and launches them:
  // `tiled` in work-groups of tile_size() over the large tiles, then of kSmallTile over the small
  // ones; `direct` one work-item a tile over the lone ones (each kernel takes `tile_offset`, its
  // first tile; `direct` also `tiles`, their count, and `tile`, the tile size).
  void launch_tiled(Kernel& tiled, Kernel& direct) const;

  // Neighbour ids within `radius` of every particle, in the store's (sorted) order. For tests.
  std::vector<std::vector<std::uint32_t>> neighbour_lists(ParticleStore& store, float radius);

  // A cell of bulk water at h = 1.2 dx holds 8 to 27 particles (2.4 dx a side): one tile.
  static constexpr std::uint32_t kDefaultTile = 32;
  // A cell of a sheet of water one or two particles deep: its own, narrower work-groups.
  static constexpr std::uint32_t kSmallTile = 8;
  // A cell of a film (a drop to a cell): one work-item walks its neighbourhood.
  static constexpr std::uint32_t kLoneTile = 2;

 private:
  void ensure_capacity(std::size_t n);
  // The radix sort's passes over keys_[0] and values_[0]; each returns which of the two buffers
  // holds the result. In runs: `blocks` work-items each walking `chunk` keys (cl/spatial_hash.cl;
  // a CPU's). In tiles: work-groups sorting tiles in local memory (cl/radix_tiles.cl; a GPU's).
  int sort_in_runs(cl_uint n, cl_uint blocks, cl_uint chunk);
  int sort_in_tiles(cl_uint n, ParticleStore& store);
  // The exclusive scan of `count` counts of a sort's histogram: one work-group on a CPU, many on a
  // wide device (cl/spatial_hash.cl).
  void scan_histogram(const cl::Buffer& hist, cl_uint count);
  // The tile list of the sort's result in keys_[in], cut into the sort's blocks.
  void build_tiles(int in, cl_uint blocks, cl_uint chunk);
  ComputeContext& compute_;
  GridSpec grid_;
  std::uint32_t dead_key_;
  int passes_, digit_bits_;  // the radix sort's passes over the keys, and the bits of each
  std::uint32_t tile_;
  std::uint32_t lone_ = kLoneTile;
  std::size_t least_chunk_, most_blocks_, scan_group_;  // the sort's cut for this device
  std::size_t slice_group_ = 0;  // a wide device's scan: work-items a slice (0: one group scans)
  bool sort_in_tiles_ = false;   // a wide device's sort (cl/radix_tiles.cl)
  cl_uint summary_host_[4] = {0, 0, 0, 0};  // live particles, large, small and lone tiles
  cl::Event summary_read_;
  bool summary_pending_ = false;
  bool per_particle_ = false;  // the last build's tiles are single particles: no list
  bool carry_depth_ = false;   // the sort gathers kDepth too (carry_water_depth)
  std::vector<ParticleField> carried_fields_;  // and these (carry_fields)
  std::uint32_t tiles_ = 0, small_tiles_ = 0, lone_tiles_ = 0;
  std::size_t capacity_ = 0;
  cl_uint sorted_ = 0;  // keys in keys_[sorted_in_] from the last build: their cells are filled
  int sorted_in_ = 0;
  static constexpr cl_uint kEmptyCell = 0xFFFFFFFFu;
  cl::Buffer keys_[2], values_[2], hist_, slice_totals_, summary_, cell_start_, cell_end_,
      tile_first_;
  Kernel hash_keys_, histogram_, scan_, scan_slice_totals_, scan_totals_, scan_slices_, scatter_,
      sort_tiles_, scatter_tiles_, reorder_, cell_bounds_, neighbour_list_, tile_count_, tile_scan_,
      tile_scatter_;
};

}  // namespace runnel
