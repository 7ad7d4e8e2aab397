// SPDX-License-Identifier: MIT
// terrain_apply against its plain C++ oracle: h_fixed + delta exactly, the delta cleared, and the
// float view (h_fixed + delta)·q rounded once, for heights far from zero and below it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runnel/terrain/device_terrain.hpp"
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

}  // namespace
}  // namespace runnel
