// SPDX-License-Identifier: MIT
// Depression handling against independent references: the basin graph's fill and the
// priority-flood both equal Planchon & Darboux's (2002) iterative fill, the plain definition
// (every vertex at the lowest level over which it can drain); D8 routing on pitted terrain sends
// every vertex to base level, downhill or level on the filled surface, lakes through their spill
// point; a cycle of receivers is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "runnel/landscape/basin_graph.hpp"
#include "runnel/landscape/flow_routing.hpp"
#include "runnel/terrain/generators.hpp"

namespace runnel {
namespace {

std::vector<double> heights_of(const Heightmap& t) {
  return {t.h.begin(), t.h.end()};
}

std::vector<std::uint8_t> outlets(int nx, int ny, BaseLevel base) {
  std::vector<std::uint8_t> o(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      o[static_cast<std::size_t>(j) * nx + i] = is_base_level(i, j, nx, ny, base);
  return o;
}

// Planchon & Darboux 2002, the direct form: start from +∞ inside, lower each vertex to the lowest
// neighbour's level (never below its own height) until nothing changes. Slow and obviously right.
std::vector<double> planchon_darboux(const std::vector<double>& h, int nx, int ny,
                                     const std::vector<std::uint8_t>& outlet) {
  std::vector<double> w(h.size(), std::numeric_limits<double>::infinity());
  for (std::size_t k = 0; k < h.size(); ++k)
    if (outlet[k]) w[k] = h[k];
  for (bool changed = true; changed;) {
    changed = false;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * nx + i;
        if (outlet[k]) continue;
        for (int b = j - 1; b <= j + 1; ++b)
          for (int a = i - 1; a <= i + 1; ++a) {
            if (a < 0 || b < 0 || a >= nx || b >= ny || (a == i && b == j)) continue;
            const double level = std::max(h[k], w[static_cast<std::size_t>(b) * nx + a]);
            if (level < w[k]) w[k] = level, changed = true;
          }
      }
  }
  return w;
}

// Steepest descent on the raw heights, as the router starts (the basin graph's input).
std::vector<std::int32_t> raw_receivers(const std::vector<double>& h, int nx, int ny,
                                        const std::vector<std::uint8_t>& outlet) {
  std::vector<std::int32_t> r(h.size());
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::int32_t k = j * nx + i;
      r[k] = k;
      if (outlet[k]) continue;
      double steepest = 0;
      for (int b = j - 1; b <= j + 1; ++b)
        for (int a = i - 1; a <= i + 1; ++a) {
          if (a < 0 || b < 0 || a >= nx || b >= ny || (a == i && b == j)) continue;
          const double s = (h[k] - h[b * nx + a]) / std::hypot(a - i, b - j);
          if (s > steepest) steepest = s, r[k] = b * nx + a;
        }
    }
  return r;
}

struct Case {
  int nx, ny;
  std::uint64_t seed;
  BaseLevel base;
};
const Case kCases[] = {{48, 40, 1, BaseLevel::kAllEdges},
                       {40, 56, 2, BaseLevel::kAllEdges},
                       {50, 30, 3, BaseLevel::kWestEast}};

// A case's pitted fBm terrain, its outlets and its exact fill (the reference).
struct Pitted {
  Heightmap terrain;
  std::vector<double> h;
  std::vector<std::uint8_t> outlet;
  std::vector<double> filled;
};
Pitted pitted(const Case& c, double cell) {
  Pitted p;
  p.terrain = generate_terrain("fbm", c.nx, c.ny, cell, c.seed, {{"relief", 0.3}});
  p.h = heights_of(p.terrain);
  p.outlet = outlets(c.nx, c.ny, c.base);
  p.filled = planchon_darboux(p.h, c.nx, c.ny, p.outlet);
  return p;
}

TEST(FlowRouting, TheBasinGraphAndThePriorityFloodFillExactlyAsPlanchonDarboux) {
  for (const Case& c : kCases) {
    const Pitted p = pitted(c, 1.0);
    const std::vector<double>&h = p.h, &reference = p.filled;
    const std::vector<std::uint8_t>& outlet = p.outlet;
    int raised = 0;
    for (std::size_t k = 0; k < h.size(); ++k) raised += reference[k] > h[k];
    ASSERT_GT(raised, 20) << "seed " << c.seed << ": the terrain must have depressions";

    std::vector<double> basin_fill;
    BasinGraph graph;
    graph.fill(h, raw_receivers(h, c.nx, c.ny, outlet), outlet, c.nx, c.ny, basin_fill);
    std::vector<double> flood = h;
    priority_flood(
        flood, c.nx, c.ny, [&](int i, int j) { return outlet[j * c.nx + i] != 0; }, 0.0);
    for (std::size_t k = 0; k < h.size(); ++k) {
      ASSERT_EQ(basin_fill[k], reference[k]) << "basin graph, seed " << c.seed << ", vertex " << k;
      ASSERT_EQ(flood[k], reference[k]) << "priority flood, seed " << c.seed << ", vertex " << k;
    }
  }
}

TEST(FlowRouting, ThePriorityFloodWithEpsilonDrainsEveryVertexAndRaisesOnlyByEpsilons) {
  const Case c = kCases[0];
  const Pitted p = pitted(c, 1.0);
  const std::vector<double>&h = p.h, &exact = p.filled;
  const std::vector<std::uint8_t>& outlet = p.outlet;
  const double epsilon = 1e-7;
  std::vector<double> f = h;
  priority_flood(
      f, c.nx, c.ny, [&](int i, int j) { return outlet[j * c.nx + i] != 0; }, epsilon);
  for (int j = 0; j < c.ny; ++j)
    for (int i = 0; i < c.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * c.nx + i;
      EXPECT_GE(f[k], exact[k]);
      EXPECT_LE(f[k], exact[k] + epsilon * static_cast<double>(h.size()));
      if (outlet[k]) continue;
      bool lower = false;
      for (int b = j - 1; b <= j + 1; ++b)
        for (int a = i - 1; a <= i + 1; ++a)
          if (a >= 0 && b >= 0 && a < c.nx && b < c.ny) lower |= f[b * c.nx + a] < f[k];
      EXPECT_TRUE(lower) << "vertex " << i << "," << j << " has no lower neighbour";
    }
}

TEST(FlowRouting, EveryVertexDrainsToBaseLevelNeverUphillOnTheFilledSurface) {
  for (const Case& c : kCases) {
    const Pitted p = pitted(c, 2.0);
    const Heightmap& t = p.terrain;
    const std::vector<double>&h = p.h, &filled = p.filled;
    const std::vector<std::uint8_t>& outlet = p.outlet;
    D8Router router(c.nx, c.ny, t.cell, c.base);
    router.route(h);  // a second call on the same router must give a full answer too
    const FlowRouting& r = router.route(h);
    std::vector<int> position(h.size(), -1);
    for (std::size_t s = 0; s < r.stack.size(); ++s) {
      ASSERT_EQ(position[r.stack[s]], -1) << "a node twice on the stack";
      position[r.stack[s]] = static_cast<int>(s);
    }
    double base_area = 0;
    for (int j = 0; j < c.ny; ++j)
      for (int i = 0; i < c.nx; ++i) {
        const std::int32_t k = j * c.nx + i, rec = r.receiver[k];
        ASSERT_GE(position[k], 0);
        if (outlet[k]) {
          EXPECT_EQ(rec, k);
          base_area += r.area[k];
          continue;
        }
        const int a = rec % c.nx, b = rec / c.nx;
        ASSERT_TRUE(rec != k && std::abs(a - i) <= 1 && std::abs(b - j) <= 1)
            << "vertex " << i << "," << j << " drains to a neighbour";
        EXPECT_DOUBLE_EQ(r.distance[k], std::hypot(a - i, b - j) * t.cell);
        EXPECT_LE(filled[rec], filled[k]) << "never uphill on the filled surface";
        EXPECT_LT(position[rec], position[k]) << "the receiver comes first on the stack";
      }
    EXPECT_NEAR(base_area, double(c.nx) * c.ny * t.cell * t.cell, 1e-6)
        << "all area reaches base level";
  }
}

TEST(FlowRouting, ALakeDrainsThroughItsSpillPoint) {
  // A 9 × 9 bowl: a ring at 10 m around a floor at 1 m, one notch at 5 m on the ring's east side;
  // the base level all round at 0 m. All the floor must leave through the notch.
  const int n = 11;
  std::vector<double> h(n * n, 0.0);
  for (int j = 1; j < n - 1; ++j)
    for (int i = 1; i < n - 1; ++i)
      h[j * n + i] = (i == 1 || j == 1 || i == n - 2 || j == n - 2) ? 10.0 : 1.0;
  const int notch = 5 * n + (n - 2);
  h[notch] = 5.0;
  const FlowRouting r = route_d8(h, n, n, 1.0);
  for (int j = 2; j < n - 2; ++j)
    for (int i = 2; i < n - 2; ++i) {
      int k = j * n + i, hops = 0;
      bool through_notch = false;
      while (r.receiver[k] != k && hops++ < n * n) {
        through_notch |= k == notch;
        k = r.receiver[k];
      }
      EXPECT_TRUE(through_notch) << "floor vertex " << i << "," << j;
    }
  EXPECT_DOUBLE_EQ(r.area[notch], 7 * 7 + 1.0) << "the notch drains the floor and itself";
}

TEST(FlowRouting, ACycleOfReceiversIsRefused) {
  FlowRouting r;
  r.receiver = {0, 2, 1, 2};  // 1 → 2 → 1
  r.distance.assign(4, 1.0);
  EXPECT_THROW(build_stack(r, std::vector<double>(4, 1.0)), std::logic_error);
}

TEST(FlowRouting, AStarOfDonorsWithinTheCountersReachIsStacked) {
  // 254 donors of node 0 fit the byte that counts them; the 255th is refused, not miscounted.
  for (int donors : {254, 255}) {
    FlowRouting r;
    r.receiver.assign(donors + 1, 0);
    r.distance.assign(donors + 1, 1.0);
    if (donors == 254) {
      build_stack(r, std::vector<double>(donors + 1, 1.0));
      EXPECT_EQ(r.stack.front(), 0);
      EXPECT_EQ(r.area[0], donors + 1.0);
    } else {
      EXPECT_THROW(build_stack(r, std::vector<double>(donors + 1, 1.0)), std::logic_error);
    }
  }
}

}  // namespace
}  // namespace runnel
