// SPDX-License-Identifier: MIT
// The spatial hash yields exactly the neighbour sets of a KD-tree radius search (nanoflann), on
// random, clustered, cell-border and out-of-grid particle sets; its sort is deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>
#include <random>
#include <set>

#include "runnel/sph/spatial_hash.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

struct Cloud {
  std::vector<float> x, y, z;
  std::size_t kdtree_get_point_count() const { return x.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t d) const {
    return d == 0 ? x[i] : d == 1 ? y[i] : z[i];
  }
  template <class B>
  bool kdtree_get_bbox(B&) const {
    return false;
  }
};

HostParticles to_particles(const Cloud& c) {
  HostParticles p;
  for (std::size_t i = 0; i < c.x.size(); ++i) p.push(c.x[i], c.y[i], c.z[i], 0, 0, 0, 1000, 1);
  return p;
}

// `count` particles uniform over [0, 4]³, drawn from rng.
HostParticles uniform_particles(std::mt19937& rng, int count) {
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  HostParticles p;
  for (int i = 0; i < count; ++i) p.push(u(rng), u(rng), u(rng), 0, 0, 0, 1000, 1);
  return p;
}

// Grid over [0, 4]³ with cell 0.25 (radius = cell, as 2h).
GridSpec test_grid() {
  const double lo[3] = {0, 0, 0}, hi[3] = {4, 4, 4};
  return GridSpec::covering(lo, hi, 0.25);
}

// The hash's neighbour lists against a kd-tree over `cloud` (particle id k at cloud point k).
void expect_kd_tree_neighbours(SpatialHash& hash, ParticleStore& store, const Cloud& cloud) {
  ASSERT_EQ(store.size(), cloud.x.size());
  const float radius = 0.25f;
  const auto lists = hash.neighbour_lists(store, radius);
  const HostParticles sorted = store.download();

  using Tree =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Cloud>, Cloud, 3>;
  Tree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  std::size_t compared = 0;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const std::uint32_t id = sorted.id[i];  // ids are the original indices
    const float q[3] = {cloud.x[id], cloud.y[id], cloud.z[id]};
    std::vector<std::pair<std::uint32_t, float>> matches;
    tree.radiusSearch(q, radius * radius, matches, nanoflann::SearchParams());
    std::set<std::uint32_t> expected, ambiguous;
    for (auto& [j, d2] : matches) {
      if (j == id) continue;
      // Pairs within round-off of the radius may fall either way in float arithmetic.
      if (std::fabs(std::sqrt(d2) - radius) < 1e-5f)
        ambiguous.insert(j);
      else
        expected.insert(j);
    }
    std::set<std::uint32_t> got(lists[i].begin(), lists[i].end());
    for (auto j : ambiguous) got.erase(j);
    ASSERT_EQ(got, expected) << "particle " << id << " at " << q[0] << "," << q[1] << "," << q[2];
    compared += expected.size();
  }
  EXPECT_GT(compared, 0u);
}

void expect_same_neighbours(const Cloud& cloud) {
  ComputeContext compute(test::test_device());
  ParticleStore store(compute, 16);  // small, so appending grows it
  store.append(to_particles(cloud));
  SpatialHash hash(compute, test_grid());
  hash.build(store);
  expect_kd_tree_neighbours(hash, store, cloud);
}

TEST(SpatialHash, RandomParticlesMatchKdTree) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 4.0f);
  Cloud c;
  for (int i = 0; i < 3000; ++i) {
    c.x.push_back(u(rng));
    c.y.push_back(u(rng));
    c.z.push_back(u(rng));
  }
  expect_same_neighbours(c);
}

// A build empties the cells the last one filled (in the key pass, at the cost of the particles)
// even when the particles grew past the hash's capacity in between: here the first particles leave
// the cells they filled for others next to them, and a stale cell there would hand their neighbours
// ranges of the wrong particles.
TEST(SpatialHash, ARebuildForgetsTheCellsTheParticlesLeftWhileTheyGrew) {
  ComputeContext compute(test::test_device());
  ParticleStore store(compute, 16);
  SpatialHash hash(compute, test_grid());
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> first(1.5f, 2.5f), later(2.0f, 3.0f), moved(3.2f, 4.0f);
  Cloud start;
  for (int i = 0; i < 200; ++i)
    start.x.push_back(first(rng)), start.y.push_back(first(rng)), start.z.push_back(first(rng));
  store.append(to_particles(start));
  hash.build(store);
  // 2,800 more next to where the first 200 were (past the hash's capacity), and those 200 moved
  // away.
  Cloud more;
  for (int i = 0; i < 2800; ++i)
    more.x.push_back(later(rng)), more.y.push_back(later(rng)), more.z.push_back(later(rng));
  std::vector<float> away[3];
  for (int i = 0; i < 200; ++i)
    for (auto& a : away) a.push_back(moved(rng));
  for (int d = 0; d < 3; ++d)
    compute.queue().enqueueWriteBuffer(store.buffer(static_cast<ParticleField>(kX + d)), CL_TRUE, 0,
                                       200 * sizeof(float), away[d].data());
  store.append(to_particles(more));
  hash.build(store);
  // The cloud by id: the first 200 ids where they moved to, the rest appended in order.
  const HostParticles now = store.download();
  Cloud cloud;
  cloud.x.resize(now.size()), cloud.y.resize(now.size()), cloud.z.resize(now.size());
  for (std::size_t i = 0; i < now.size(); ++i) {
    cloud.x[now.id[i]] = now.f[kX][i];
    cloud.y[now.id[i]] = now.f[kY][i];
    cloud.z[now.id[i]] = now.f[kZ][i];
  }
  for (std::uint32_t id = 0; id < 200; ++id) ASSERT_GE(cloud.x[id], 3.2f) << id;
  expect_kd_tree_neighbours(hash, store, cloud);
}

TEST(SpatialHash, ClusteredParticlesWithEmptyCellsMatchKdTree) {
  std::mt19937 rng(2);
  std::normal_distribution<float> g(0.0f, 0.15f);
  Cloud c;
  const float centres[3][3] = {{1, 1, 1}, {3, 2.5f, 1.5f}, {2, 3.2f, 3.2f}};
  for (auto& centre : centres) {
    for (int i = 0; i < 800; ++i) {
      c.x.push_back(centre[0] + g(rng));
      c.y.push_back(centre[1] + g(rng));
      c.z.push_back(centre[2] + g(rng));
    }
  }
  expect_same_neighbours(c);
}

TEST(SpatialHash, ParticlesOnCellBordersAndOutsideTheGridMatchKdTree) {
  Cloud c;
  // Exactly on cell borders: a lattice with the cell's own spacing, offset by half a radius.
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) {
      for (int k = 0; k < 3; ++k) {
        c.x.push_back(0.25f * i);
        c.y.push_back(0.25f * j);
        c.z.push_back(0.125f * k + 1.0f);
      }
    }
  }
  // Outside the grid on every side, some far away, some clustered just past an edge.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.6f, 0.0f), far(5.0f, 50.0f);
  for (int i = 0; i < 400; ++i) {
    c.x.push_back(u(rng));
    c.y.push_back(2.0f + u(rng));
    c.z.push_back(4.0f - u(rng));
    c.x.push_back(far(rng));
    c.y.push_back(-far(rng));
    c.z.push_back(1.0f);
  }
  expect_same_neighbours(c);
}

TEST(SpatialHash, SortIsByCellAndDeterministic) {
  ComputeContext compute(test::test_device());
  std::mt19937 rng(4);
  HostParticles p = uniform_particles(rng, 5000);
  std::vector<std::uint32_t> orders[2];
  for (auto& order : orders) {
    ParticleStore store(compute);
    store.append(p);
    SpatialHash hash(compute, test_grid());
    hash.build(store);
    order = store.download().id;
  }
  EXPECT_EQ(orders[0], orders[1]);
  // Sorted by the linear cell index (x fastest), and stable: within one cell, ids (original
  // order) ascend.
  ParticleStore store(compute);
  store.append(p);
  SpatialHash hash(compute, test_grid());
  hash.build(store);
  const HostParticles s = store.download();
  auto cell = [](float v) { return std::min(15, static_cast<int>(v / 0.25f)); };
  for (std::size_t i = 1; i < s.size(); ++i) {
    const bool same = cell(s.f[kX][i]) == cell(s.f[kX][i - 1]) &&
                      cell(s.f[kY][i]) == cell(s.f[kY][i - 1]) &&
                      cell(s.f[kZ][i]) == cell(s.f[kZ][i - 1]);
    if (same) {
      ASSERT_LT(s.id[i - 1], s.id[i]);
    }
    auto linear = [&](std::size_t k) {
      return cell(s.f[kX][k]) + 16 * (cell(s.f[kY][k]) + 16 * cell(s.f[kZ][k]));
    };
    ASSERT_LE(linear(i - 1), linear(i));
  }
}

// The sort against std::stable_sort of the particles' cells, cut as a CPU cuts it (a few long runs,
// one work-item scanning the histogram) and as a GPU does (thousands of short runs, the histogram
// of a million counts scanned over many work-groups, in tiles): the same order, the reference's.
// On grids of 1, 8³, 16³, 64³ and 128³ cells over [0, 4]³, whose keys (1, 10, 13, 19 and 22 bits) a
// CPU sorts in one pass of 1 bit, one of 10, two of 7, two of 10 and three of 8, and a GPU (digits
// of at most 9 bits) in one of 1, two of 5, two of 7, three of 7 and three of 8. (One cell: every
// key is 0, the order the particles came in.)
TEST(SpatialHash, SortMatchesAStableSortOnEitherDevicesCut) {
  std::mt19937 rng(11);
  std::normal_distribution<float> clump(1.3f, 0.2f);  // crowded cells and empty ones
  HostParticles p = uniform_particles(rng, 150000);
  for (int i = 0; i < 50000; ++i) p.push(clump(rng), clump(rng), clump(rng), 0, 0, 0, 1000, 1);
  const struct {
    int cells, bits, passes[2], digit_bits[2];  // [a CPU's, a GPU's]
  } grids[] = {{1, 1, {1, 1}, {1, 1}},
               {8, 10, {1, 2}, {10, 5}},
               {16, 13, {2, 2}, {7, 7}},
               {64, 19, {2, 3}, {10, 7}},
               {128, 22, {3, 3}, {8, 8}}};
  for (const auto& g : grids) {
    const double lo[3] = {0, 0, 0}, hi[3] = {4, 4, 4};
    const GridSpec grid = GridSpec::covering(lo, hi, 4.0 / g.cells);
    ASSERT_EQ(grid.key_bits(), g.bits);
    const float size = 4.0f / g.cells;  // a power of two: v / size is the kernel's v · (1 / size)
    auto cell = [&](float v) { return std::clamp(static_cast<int>(v / size), 0, g.cells - 1); };
    std::vector<std::uint32_t> expected(p.size());
    for (std::uint32_t i = 0; i < expected.size(); ++i) expected[i] = i;
    auto key = [&](std::uint32_t i) {
      return cell(p.f[kX][i]) + g.cells * (cell(p.f[kY][i]) + g.cells * cell(p.f[kZ][i]));
    };
    std::stable_sort(expected.begin(), expected.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
    for (bool wide : {false, true}) {
      ComputeContext compute(test::test_device());
      compute.set_wide(wide);
      ParticleStore store(compute);
      store.append(p);
      SpatialHash hash(compute, grid);
      EXPECT_EQ(hash.radix_passes(), g.passes[wide]);
      EXPECT_EQ(hash.radix_digit_bits(), g.digit_bits[wide]);
      hash.build(store);
      ASSERT_EQ(store.download().id, expected)
          << (wide ? "a GPU's cut" : "a CPU's cut") << ", " << g.cells << "³ cells";
    }
  }
}

// The build in two halves: until finish_build() the store still counts the dead particles, sorted
// to its end with their flag, and the tile counts are the last build's; then it holds the live
// ones in the order build() leaves them.
TEST(SpatialHash, ASplitBuildDropsTheDeadWhenItFinishes) {
  ComputeContext compute(test::test_device());
  std::mt19937 rng(5);
  HostParticles p = uniform_particles(rng, 3000);
  std::size_t live = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.id[i] = static_cast<std::uint32_t>(i) | (i % 3 == 0 ? kDeadFlag : 0u);
    live += i % 3 != 0;
  }
  ParticleStore whole(compute), split(compute);
  whole.upload(p);
  split.upload(p);
  SpatialHash one(compute, test_grid()), two(compute, test_grid());
  one.build(whole);
  two.begin_build(split);
  EXPECT_EQ(split.size(), p.size());
  EXPECT_EQ(two.tile_count(), 0u);  // no build has finished yet
  const HostParticles during = split.download();
  for (std::size_t i = 0; i < during.size(); ++i)
    ASSERT_EQ((during.id[i] & kDeadFlag) != 0, i >= live) << i;
  two.finish_build(split);
  EXPECT_EQ(split.size(), live);
  EXPECT_EQ(whole.size(), live);
  EXPECT_EQ(split.download().id, whole.download().id);
  EXPECT_EQ(two.tile_count(), one.tile_count());
  EXPECT_GT(one.tile_count(), 0u);
}

// The tiles the neighbour passes run on: every cell's particles, in runs of at most the tile size
// starting at the cell's first particle, each particle in exactly one tile, those of more than
// kSmallTile particles listed first, then those of more than kLoneTile, then the lone ones;
// against lists made here from the sorted positions.
TEST(SpatialHash, TilesCoverEachCellInRunsOfTheTileSize) {
  ComputeContext compute(test::test_device());
  std::mt19937 rng(9);
  std::normal_distribution<float> clump(2.0f, 0.05f);  // cells of 100+ particles: several tiles
  HostParticles p = uniform_particles(rng, 3000);
  for (int i = 0; i < 1000; ++i) p.push(clump(rng), clump(rng), clump(rng), 0, 0, 0, 1000, 1);
  for (std::uint32_t tile : {1u, 7u, 32u}) {
    ParticleStore store(compute);
    store.append(p);
    SpatialHash hash(compute, test_grid(), tile);
    hash.build(store);
    const HostParticles s = store.download();
    auto cell = [&](std::size_t i) {
      auto c = [](float v) { return std::min(15, static_cast<int>(v / 0.25f)); };
      return c(s.f[kX][i]) + 16 * (c(s.f[kY][i]) + 16 * c(s.f[kZ][i]));
    };
    std::vector<std::uint32_t> large, small, lone;
    for (std::size_t begin = 0, end = 0; begin < s.size(); begin = end) {
      end = begin;
      while (end < s.size() && cell(end) == cell(begin)) ++end;
      for (std::size_t t = begin; t < end; t += tile) {
        const std::size_t size = std::min<std::size_t>(tile, end - t);
        (size > SpatialHash::kSmallTile  ? large
         : size > SpatialHash::kLoneTile ? small
                                         : lone)
            .push_back(static_cast<std::uint32_t>(t));
      }
    }
    ASSERT_FALSE(lone.empty());  // the case covers all three kinds
    ASSERT_EQ(hash.small_tile_count(), small.size()) << "tile " << tile;
    ASSERT_EQ(hash.lone_tile_count(), lone.size()) << "tile " << tile;
    ASSERT_EQ(hash.tile_count(), large.size() + small.size() + lone.size()) << "tile " << tile;
    if (tile == 1) continue;  // every particle its own lone tile: the list is not built
    std::vector<std::uint32_t> first(hash.tile_count());
    compute.queue().enqueueReadBuffer(hash.tile_first(), CL_TRUE, 0, first.size() * 4,
                                      first.data());
    large.insert(large.end(), small.begin(), small.end());
    large.insert(large.end(), lone.begin(), lone.end());
    EXPECT_EQ(first, large) << "tile " << tile;
  }
}

}  // namespace
}  // namespace runnel
