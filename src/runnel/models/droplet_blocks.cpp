// SPDX-License-Identifier: MIT
#include "runnel/models/droplet_blocks.hpp"

#include <algorithm>
#include <cmath>

namespace runnel {

int DropletBlocks::rows_for(double radius) {
  const int reach = std::max(1, static_cast<int>(std::ceil(radius)));
  return 2 * reach + 1;
}

DropletBlocks DropletBlocks::layout(int nx, int ny, double radius, unsigned compute_units) {
  DropletBlocks b;
  b.rows = rows_for(radius);
  b.blocks_y = (ny + b.rows - 1) / b.rows;
  // Whole rows keep a work-item's brushes in a band of the map the cache holds; a device with
  // many compute units gets more, shorter runs.
  const std::size_t units = std::max(1u, compute_units);
  for (int runs = 1;; ++runs) {
    b.width = std::max(b.rows, (nx + runs - 1) / runs);
    b.blocks_x = (nx + b.width - 1) / b.width;
    if (b.per_parity() >= 32 * units || b.width == b.rows) break;
  }
  // Many groups a compute unit: a block's work varies with its droplets, and a unit that finishes
  // early takes the next group.
  const std::size_t per_unit = b.per_parity() / (32 * units);
  while (b.group * 2 <= std::min<std::size_t>(per_unit, 64)) b.group *= 2;
  return b;
}

}  // namespace runnel
