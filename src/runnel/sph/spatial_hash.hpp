// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
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
  int key_bits() const;  // Morton bits of a live key, plus one for the dead key
};

// Host side of cl/spatial_hash.cl: sorts particles by the Morton key of their cell with a
// deterministic stable radix sort, gathers every persistent field into that order, drops dead
// particles, and builds the cell start/end tables that the neighbour loops read. Owns no particle
// data (CompactNSearch's lesson): it only computes an order and cell ranges for the store.
class SpatialHash {
 public:
  SpatialHash(ComputeContext& compute, const GridSpec& grid);

  // Sorts and reorders `store` in place; afterwards store.size() counts live particles only.
  void build(ParticleStore& store);

  const GridSpec& grid() const { return grid_; }
  const cl::Buffer& cell_start() const { return cell_start_; }
  const cl::Buffer& cell_end() const { return cell_end_; }
  // The grid arguments every kernel that hashes a position takes: ox, oy, oz, inv_cell, gx, gy, gz.
  void bind_grid(Kernel& kernel) const;
  // The grid and its cell ranges (cell_start, cell_end): what a neighbour loop walks.
  void bind_cells(Kernel& kernel) const;

  // Neighbour ids within `radius` of every particle, in the store's (sorted) order. For tests.
  std::vector<std::vector<std::uint32_t>> neighbour_lists(ParticleStore& store, float radius);

  static constexpr std::uint32_t kRadixBlocks = 256;

 private:
  void ensure_capacity(std::size_t n);
  ComputeContext& compute_;
  GridSpec grid_;
  std::uint32_t dead_key_;
  int passes_;
  std::size_t capacity_ = 0;
  cl::Buffer keys_[2], values_[2], hist_, alive_, cell_start_, cell_end_;
  Kernel hash_keys_, histogram_, scan_, scatter_, reorder_, cell_bounds_, neighbour_list_;
};

}  // namespace runnel
