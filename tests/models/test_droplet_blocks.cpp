// SPDX-License-Identifier: MIT
// droplet_apply's blocks (DropletBlocks): every droplet's changes land in its block's reach, and
// two blocks of one parity launch never reach the same vertex, checked by brute force over the
// vertices each block's droplets can touch, for CPU-like and GPU-like devices and several radii.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "runnel/models/droplet_blocks.hpp"

namespace runnel {
namespace {

// The vertices a droplet in cell (i, j) can change, as droplet.cl's kernels do: its brush covers
// cells ci − r .. ci + r + 1 (r = ceil(radius)), a deposit at its cell the corners i .. i + 1, and
// the deposit at the end of its life the corners of the cell it moved to, one cell away at most.
struct Reach {
  int lo, hi;
};
Reach reach_of(int cell, double radius) {
  const int r = static_cast<int>(std::ceil(radius));
  return {std::min(cell - r, cell - 1), std::max(cell + r + 1, cell + 2)};
}

TEST(DropletBlocks, BlocksOfOneParityNeverTouchTheSameVertex) {
  struct Case {
    int nx, ny;
    double radius;
    unsigned units;
  };
  for (const Case& c : {Case{129, 129, 3, 2}, Case{1025, 1025, 3, 2}, Case{1025, 1025, 3, 132},
                        Case{257, 65, 0.5, 16}, Case{100, 300, 8, 2}, Case{65, 65, 2.5, 80}}) {
    const DropletBlocks b = DropletBlocks::layout(c.nx, c.ny, c.radius, c.units);
    SCOPED_TRACE(testing::Message() << c.nx << "×" << c.ny << " radius " << c.radius << ", "
                                    << c.units << " units: blocks " << b.rows << "×" << b.width);
    ASSERT_GE(b.width, b.rows);
    // Owner of every vertex per parity launch: -1, or the block that reaches it.
    for (int parity = 0; parity < 4; ++parity) {
      std::vector<int> owner(static_cast<std::size_t>(c.nx) * c.ny, -1);
      int blocks = 0;
      for (int by = parity >> 1; by < b.blocks_y; by += 2) {
        for (int bx = parity & 1; bx < b.blocks_x; bx += 2) {
          ++blocks;
          // Droplets sit in cells 0 .. n − 2 (their cell's far corners are on the map).
          const int i0 = bx * b.width, i1 = std::min((bx + 1) * b.width, c.nx - 1) - 1;
          const int j0 = by * b.rows, j1 = std::min((by + 1) * b.rows, c.ny - 1) - 1;
          if (i0 > i1 || j0 > j1) continue;
          ASSERT_EQ(b.block_of(i0, j0), by * b.blocks_x + bx);
          ASSERT_EQ(b.block_of(i1, j1), by * b.blocks_x + bx);
          const Reach x = {reach_of(i0, c.radius).lo, reach_of(i1, c.radius).hi};
          const Reach z = {reach_of(j0, c.radius).lo, reach_of(j1, c.radius).hi};
          for (int j = std::max(z.lo, 0); j <= std::min(z.hi, c.ny - 1); ++j) {
            for (int i = std::max(x.lo, 0); i <= std::min(x.hi, c.nx - 1); ++i) {
              int& o = owner[static_cast<std::size_t>(j) * c.nx + i];
              ASSERT_TRUE(o < 0 || o == by * b.blocks_x + bx)
                  << "vertex (" << i << ", " << j << ") reached by blocks " << o << " and "
                  << by * b.blocks_x + bx << " in parity " << parity;
              o = by * b.blocks_x + bx;
            }
          }
        }
      }
      EXPECT_EQ(b.has_parity(parity), blocks > 0) << "parity " << parity;
      EXPECT_LE(static_cast<std::size_t>(blocks), b.per_parity());
    }
    // Enough work-items for the device: a launch has at least 32 blocks per compute unit where
    // the map has room for them.
    EXPECT_TRUE(b.per_parity() >= 32 * c.units || b.width == b.rows) << b.per_parity();
    EXPECT_GE(b.group, 1u);
    EXPECT_LE(b.group, 64u);
  }
}

// On a 2-core CPU the blocks are whole rows of the map (a work-item's brushes stay in one band
// the cache holds); on a GPU with many compute units the rows are cut into runs.
TEST(DropletBlocks, WholeRowsOnAFewCoresAndRunsOnManyUnits) {
  const DropletBlocks cpu = DropletBlocks::layout(1025, 1025, 3, 2);
  EXPECT_EQ(cpu.rows, 7);
  EXPECT_EQ(cpu.blocks_x, 1);
  EXPECT_EQ(cpu.group, 1u);
  const DropletBlocks gpu = DropletBlocks::layout(1025, 1025, 3, 132);
  EXPECT_GT(gpu.blocks_x, 8);
  EXPECT_EQ(gpu.rows, 7);
}

}  // namespace
}  // namespace runnel
