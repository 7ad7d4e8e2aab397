// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>

namespace runnel {

// The blocks droplet_apply adds a lockstep step's changes in (cl/models/droplet.cl): `rows` rows
// by `width` columns of cells. A droplet in cell (i, j) changes vertices within `reach` cells of
// it and one more beyond (its brush, at most `reach` = ceil(radius) cells out, and the deposit at
// the end of its life a cell on), so blocks `rows` ≥ 2·reach + 1 high and at least as wide, taken
// in four launches of one column and row parity each, never touch a vertex of one another: each
// block's droplets are added by one work-item with plain integer adds.
struct DropletBlocks {
  int rows = 1, width = 1;         // cells
  int blocks_x = 1, blocks_y = 1;  // over the map
  std::size_t group = 1;           // work-items per work-group of a parity launch (at most 64)

  // Blocks for an nx × ny map and a brush of `radius` cells on a device of `compute_units`: whole
  // rows of the map where that gives each launch 32 blocks per compute unit, shorter runs where it
  // does not (a GPU), never narrower than `rows`; groups small enough that every compute unit
  // gets about 32.
  static DropletBlocks layout(int nx, int ny, double radius, unsigned compute_units);
  // The fewest rows (and columns) a block may have for a brush of `radius` cells: 2·reach + 1.
  static int rows_for(double radius);
  std::size_t count() const {
    return static_cast<std::size_t>(blocks_x) * static_cast<std::size_t>(blocks_y);
  }
  // Work-items of one parity launch (those past the map's last block do nothing).
  std::size_t per_parity() const {
    return static_cast<std::size_t>((blocks_x + 1) / 2) *
           static_cast<std::size_t>((blocks_y + 1) / 2);
  }
  // Whether a launch of this parity (column parity in bit 0, row parity in bit 1) has a block.
  bool has_parity(int parity) const {
    return ((parity & 1) == 0 || blocks_x > 1) && ((parity >> 1) == 0 || blocks_y > 1);
  }
  // The block of cell (i, j), as droplet_move numbers it.
  int block_of(int i, int j) const { return (j / rows) * blocks_x + i / width; }
};

}  // namespace runnel
