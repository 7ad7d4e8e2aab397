// SPDX-License-Identifier: MIT
// Olsen 2004's cellular-automaton erosion in OpenCL: terrain + sediment conserved exactly, water
// gathers where the terrain is low, deterministic, and the model smooths by eroding highs.
#include <gtest/gtest.h>

#include <numeric>

#include "runnel/models/olsen_model.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

TEST(OlsenModel, ConservesTerrainPlusSedimentExactly) {
  const Heightmap t = generate_terrain("fbm", 97, 97, 1.0, 2, {{"relief", 0.1}});
  OlsenModel model(compute(), Parameters(), t);
  DeviceTerrain& terrain = model.state().terrain();
  const auto before = terrain.download_fixed();
  for (int k = 0; k < 200; ++k) model.step();
  const auto after = terrain.download_fixed();
  const long long h0 = std::accumulate(before.begin(), before.end(), 0LL);
  const long long h1 = std::accumulate(after.begin(), after.end(), 0LL);
  EXPECT_NE(before, after) << "the model erodes";
  EXPECT_EQ(h1 + model.suspended_quanta(), h0);
  // Water gathers in the lowest cells: the wettest cell is lower than the mean terrain.
  const auto water = model.water();
  const std::size_t wettest = std::max_element(water.begin(), water.end()) - water.begin();
  const Heightmap now = terrain.download();
  double mean = 0;
  for (float v : now.h) mean += v;
  mean /= now.size();
  EXPECT_LT(now.h[wettest], mean);
}

TEST(OlsenModel, IsDeterministic) {
  std::vector<std::vector<std::int64_t>> results;
  for (int run = 0; run < 2; ++run) {
    OlsenModel model(compute(), Parameters(),
                     generate_terrain("ridged", 65, 65, 1.0, 4, {{"relief", 0.2}}));
    for (int k = 0; k < 100; ++k) model.step();
    results.push_back(model.state().terrain().download_fixed());
  }
  EXPECT_EQ(results[0], results[1]);
}

}  // namespace
}  // namespace runnel
