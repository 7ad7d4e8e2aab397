// SPDX-License-Identifier: MIT
// terrain_apply against its plain C++ oracle: h_fixed + delta exactly, the delta cleared, and the
// float view (h_fixed + delta)·q rounded once, for heights far from zero and below it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "runnel/core/parameters.hpp"
#include "runnel/models/droplet_model.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/terrain/device_terrain.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

TEST(TerrainApply, AddsTheDeltasExactlyAndRefreshesTheFloatView) {
  const int nx = 37, ny = 23;
  const double quantum = 1e-6;
  DeviceTerrain terrain(compute(), Heightmap(nx, ny, 1.0), quantum);
  std::mt19937_64 rng(8);
  // Heights from −3 km to +9 km in micrometre quanta: far beyond a float's 24 bits of integer.
  std::uniform_int_distribution<std::int64_t> height(-3'000'000'000LL, 9'000'000'000LL),
      change(-5'000'000, 5'000'000);
  std::vector<std::int64_t> fixed(nx * ny), delta(nx * ny);
  for (auto& h : fixed) h = height(rng);
  for (auto& d : delta) d = change(rng);
  terrain.upload_fixed(fixed);
  compute().queue().enqueueWriteBuffer(terrain.delta(), CL_TRUE, 0, delta.size() * 8, delta.data());
  terrain.apply();
  const std::vector<std::int64_t> after = terrain.download_fixed();
  const Heightmap view = terrain.download();
  std::vector<std::int64_t> cleared(delta.size(), -1);
  compute().queue().enqueueReadBuffer(terrain.delta(), CL_TRUE, 0, cleared.size() * 8,
                                      cleared.data());
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    ASSERT_EQ(after[k], fixed[k] + delta[k]);
    ASSERT_EQ(cleared[k], 0);
    const double metres = static_cast<double>(after[k]) * quantum;
    // The high and low parts each round once: within two float ulps of the exact height.
    ASSERT_NEAR(view.h[k], metres, 2.5e-7 * std::fabs(metres) + 1e-9) << k;
  }
}

// A terrain whose heights a model writes directly (the grid models; no kernel ever given the
// deltas) refreshes only the view: the same view terrain_apply computes, bit for bit, and fresh
// normals.
TEST(TerrainApply, HeightsWrittenDirectlyRefreshTheViewAsTheDeltaPathDoes) {
  const int nx = 37, ny = 23;
  const double quantum = 1e-6;
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<std::int64_t> height(-3'000'000'000LL, 9'000'000'000LL);
  std::vector<std::int64_t> fixed(nx * ny);
  for (auto& h : fixed) h = height(rng);
  DeviceTerrain direct(compute(), Heightmap(nx, ny, 1.0), quantum);
  direct.normal();  // fresh normals of the flat start: apply() must make them stale
  compute().queue().enqueueWriteBuffer(direct.height_fixed(), CL_TRUE, 0, fixed.size() * 8,
                                       fixed.data());
  direct.apply();
  DeviceTerrain by_deltas(compute(), Heightmap(nx, ny, 1.0), quantum);
  std::vector<std::int64_t> zero(nx * ny, 0);
  by_deltas.upload_fixed(zero);
  compute().queue().enqueueWriteBuffer(by_deltas.delta(), CL_TRUE, 0, fixed.size() * 8,
                                       fixed.data());
  by_deltas.apply();  // the delta() call above put it on the full path
  const Heightmap a = direct.download(), b = by_deltas.download();
  EXPECT_EQ(direct.download_fixed(), fixed);
  for (std::size_t k = 0; k < fixed.size(); ++k) ASSERT_EQ(a.h[k], b.h[k]) << k;
  const std::vector<float> normals = direct.download_normals();
  const std::vector<float> oracle = terrain_normals_reference(a);
  for (std::size_t k = 0; k < normals.size(); ++k)
    ASSERT_NEAR(normals[k], oracle[k], 2e-5) << k / 3;
}

// apply_changed applies the deltas of the tiles marked changed and leaves the others: a kernel that
// adds deltas must mark their tiles (mark_changed_tiles), and this is what it relies on.
TEST(TerrainApply, ApplyChangedTouchesOnlyTheMarkedTiles) {
  const int nx = 50, ny = 40;  // 4 × 3 tiles of 16, the last ones partial
  DeviceTerrain terrain(compute(), Heightmap(nx, ny, 1.0), 1e-6);
  ASSERT_EQ(terrain.tiles_x(), 4);
  ASSERT_EQ(terrain.tiles_y(), 3);
  std::vector<std::int64_t> delta(nx * ny, 7);
  compute().queue().enqueueWriteBuffer(terrain.delta(), CL_TRUE, 0, delta.size() * 8, delta.data());
  std::vector<cl_uint> marked(12, 0);
  marked[1 * 4 + 3] = 1;  // the tile of vertices i 48..49, j 16..31
  compute().queue().enqueueWriteBuffer(terrain.changed_tiles(), CL_TRUE, 0, marked.size() * 4,
                                       marked.data());
  terrain.apply_changed();
  const auto fixed = terrain.download_fixed();
  compute().queue().enqueueReadBuffer(terrain.delta(), CL_TRUE, 0, delta.size() * 8, delta.data());
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const bool in_tile = i >= 48 && j >= 16 && j < 32;
      ASSERT_EQ(fixed[j * nx + i], in_tile ? 7 : 0) << i << " " << j;
      ASSERT_EQ(delta[j * nx + i], in_tile ? 0 : 7) << i << " " << j;
    }
  }
  std::vector<cl_uint> after(12, 9);
  compute().queue().enqueueReadBuffer(terrain.changed_tiles(), CL_TRUE, 0, after.size() * 4,
                                      after.data());
  EXPECT_EQ(after, std::vector<cl_uint>(12, 0)) << "the marks are cleared once applied";
}

// The contact surface's vertex heights that the terrain keeps for the SPH drift (a particle's
// radius r above it along the normal): bit for bit h + r / max(n_y, 0.2) of the current view and
// normals, as cl/terrain_sample.cl's offset_surface computes them in every call, also on a cliff
// whose normal is bounded and after a change to one tile refreshed them.
TEST(TerrainApply, KeptContactHeightsAreTheOffsetSurfacesAfterEveryChange) {
  const int nx = 50, ny = 40;
  Heightmap start(nx, ny, 1.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) start.at(i, j) = 0.05f * i + (i >= 30 ? 20.0f : 0.0f);  // a cliff
  DeviceTerrain terrain(compute(), start, 1e-6);
  const float radius = 0.3f;
  terrain.carry_contact_surface(radius);
  auto expect_offset_surface = [&](const char* when) {
    std::vector<float> contact(nx * ny);
    compute().queue().enqueueReadBuffer(terrain.contact(), CL_TRUE, 0, contact.size() * 4,
                                        contact.data());
    const Heightmap view = terrain.download();
    const std::vector<float> normal = terrain.download_normals();
    int bounded = 0, differing = 0, first = -1;
    for (int k = 0; k < nx * ny; ++k) {
      bounded += normal[3 * k + 1] < 0.2f;
      if (contact[k] != view.h[k] + radius / std::max(normal[3 * k + 1], 0.2f)) {
        if (differing++ == 0) first = k;
      }
    }
    EXPECT_EQ(differing, 0) << when << ": first at vertex " << first;
    EXPECT_GT(bounded, 0) << when << ": the cliff's normals must be bounded";
    return contact;
  };
  const std::vector<float> before = expect_offset_surface("at the start");
  // Half a metre onto the tile of vertices i 16..31, j 16..31, through the deltas.
  std::vector<std::int64_t> delta(nx * ny, 0);
  for (int j = 16; j < 32; ++j)
    for (int i = 16; i < 32; ++i) delta[j * nx + i] = 500'000;
  compute().queue().enqueueWriteBuffer(terrain.delta(), CL_TRUE, 0, delta.size() * 8, delta.data());
  std::vector<cl_uint> marked(4 * 3, 0);
  marked[1 * 4 + 1] = 1;
  compute().queue().enqueueWriteBuffer(terrain.changed_tiles(), CL_TRUE, 0, marked.size() * 4,
                                       marked.data());
  terrain.apply_changed();
  const std::vector<float> after = expect_offset_surface("after the change");
  EXPECT_NEAR(after[20 * nx + 20] - before[20 * nx + 20], 0.5, 1e-5);
}

// After droplet batches that touch part of a terrain, every vertex is consistent: no delta left
// behind (every tile that got one was marked), the float view equals the fixed-point heights, and
// the normals equal the oracle's for the final terrain (the stale tiles and their neighbours were
// refreshed).
TEST(TerrainApply, AfterDropletBatchesNoDeltaIsLeftAndTheNormalsAreFresh) {
  const Heightmap hills = generate_terrain("fbm", 90, 70, 1.0, 3, {{"relief", 0.3}});
  Parameters p = default_parameters();
  p.set("droplet.batch", std::int64_t{6});
  p.set("droplet.lifetime", std::int64_t{20});
  DropletModel model(compute(), p, hills);
  DeviceTerrain& terrain = model.state().terrain();
  terrain.normal();  // fresh normals of the initial terrain: only the droplets' tiles go stale
  for (int batch = 0; batch < 3; ++batch) model.step();
  const std::size_t n = hills.size();
  std::vector<std::int64_t> delta(n, -1);
  compute().queue().enqueueReadBuffer(terrain.delta(), CL_TRUE, 0, n * 8, delta.data());
  EXPECT_EQ(std::count(delta.begin(), delta.end(), 0), static_cast<std::ptrdiff_t>(n));
  const auto fixed = terrain.download_fixed();
  const Heightmap view = terrain.download();
  std::size_t changed = 0;
  const auto initial = model.state().initial_fixed();
  for (std::size_t k = 0; k < n; ++k) {
    changed += fixed[k] != initial[k];
    const double metres = static_cast<double>(fixed[k]) * terrain.quantum();
    ASSERT_NEAR(view.h[k], metres, 2.5e-7 * std::fabs(metres) + 1e-9) << k;
  }
  EXPECT_GT(changed, 50u) << "the droplets changed the terrain";
  EXPECT_LT(changed, n / 2) << "and only part of it, so some tiles stayed untouched";
  const std::vector<float> normals = terrain.download_normals();
  const std::vector<float> oracle = terrain_normals_reference(view);
  for (std::size_t k = 0; k < normals.size(); ++k)
    ASSERT_NEAR(normals[k], oracle[k], 2e-5) << k / 3;
}

}  // namespace
}  // namespace runnel
