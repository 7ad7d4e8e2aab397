// SPDX-License-Identifier: MIT
// Olsen 2004's cellular-automaton erosion in OpenCL: terrain + sediment conserved exactly, water
// gathers where the terrain is low, deterministic, and the model smooths by eroding highs.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "runnel/models/olsen_model.hpp"
#include "runnel/models/olsen_reference.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

TEST(OlsenModel, ConservesTerrainPlusSedimentExactly) {
  const Heightmap t = generate_terrain("fbm", 97, 97, 1.0, 2, {{"relief", 0.1}});
  OlsenModel model(compute(), default_parameters(), t);
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

// The outflow pass shares at most kOlsenSendable quanta of a cell's sediment (32-bit arithmetic,
// olsen.cl). A fine quantum and strong dissolution put several times that in a cell: conservation
// stays exact and the kernels still follow the oracle (which applies the same rule in 64 bits and
// double precision; an overflow would send wrapped amounts, millions of quanta off).
TEST(OlsenModel, FollowsTheOracleWhenACellHoldsMoreSedimentThanOnePassShares) {
  const int nx = 33, ny = 33;
  const Heightmap t = generate_terrain("fbm", nx, ny, 1.0, 3, {{"relief", 0.5}});
  Parameters p = default_parameters();
  p.set("erosion.height_quantum", 1e-10, "test");
  p.set("olsen.solubility", 1.0, "test");
  p.set("olsen.capacity", 100.0, "test");
  p.set("olsen.rain", 0.5, "test");
  OlsenModel model(compute(), p, t);
  DeviceTerrain& terrain = model.state().terrain();
  olsen_reference::State ref{terrain.download_fixed(), std::vector<std::int64_t>(t.size(), 0),
                             std::vector<double>(t.size(), 0.0)};
  const long long h0 = std::accumulate(ref.height.begin(), ref.height.end(), 0LL);
  for (int k = 0; k < 6; ++k) {
    model.step();
    olsen_reference::iterate(ref, nx, ny, OlsenSettings::from(p), terrain.quantum());
    const auto fixed = terrain.download_fixed();
    EXPECT_EQ(std::accumulate(fixed.begin(), fixed.end(), 0LL) + model.suspended_quanta(), h0)
        << "step " << k;
  }
  const auto sediment = model.state().download_int64(kSedimentSuspended);
  const long long most = *std::max_element(ref.sediment.begin(), ref.sediment.end());
  EXPECT_GT(most, 4 * kOlsenSendable) << "the case must put more than the cap in a cell";
  long long worst = 0;
  for (std::size_t k = 0; k < sediment.size(); ++k)
    worst = std::max(worst, std::llabs(sediment[k] - ref.sediment[k]));
  // float32 against double: the dissolved amounts, the bulk of the sediment, are K_s·w/q of a float
  // water depth that has gone through six iterations of roundings of 2^-24 (4e-6 measured); a
  // wrapped 32-bit share would be off by up to 2^31 quanta.
  EXPECT_LE(static_cast<double>(worst), 1e-5 * static_cast<double>(most)) << "quanta, of " << most;
}

TEST(OlsenModel, IsDeterministic) {
  std::vector<std::vector<std::int64_t>> results;
  for (int run = 0; run < 2; ++run) {
    OlsenModel model(compute(), default_parameters(),
                     generate_terrain("ridged", 65, 65, 1.0, 4, {{"relief", 0.2}}));
    for (int k = 0; k < 100; ++k) model.step();
    results.push_back(model.state().terrain().download_fixed());
  }
  EXPECT_EQ(results[0], results[1]);
}

// Three iterations on a random rough terrain against the plain C++ oracle (olsen_reference).
TEST(OlsenModel, IterationsMatchThePlainCppReference) {
  const int nx = 21, ny = 17;
  const Heightmap rough = test::rough_terrain(nx, ny, 0.3f, 3);
  Parameters p = default_parameters();
  p.set("olsen.solubility", 0.05);  // enough erosion per iteration to test the sediment paths
  OlsenModel model(compute(), p, rough);
  DeviceTerrain& terrain = model.state().terrain();
  olsen_reference::State ref{terrain.download_fixed(), std::vector<std::int64_t>(rough.size(), 0),
                             std::vector<double>(rough.size(), 0.0)};
  const auto before = ref.height;
  for (int iteration = 0; iteration < 3; ++iteration) {
    model.step();
    olsen_reference::iterate(ref, nx, ny, OlsenSettings::from(p), terrain.quantum());
  }
  const auto h = test::compare_quanta(terrain.download_fixed(), ref.height, before);
  EXPECT_GT(h.changed, nx * ny / 2);
  EXPECT_LE(h.worst, 4);
  EXPECT_GT(h.exact_share, 0.9);
  const auto s = test::compare_quanta(model.state().download_int64(kSedimentSuspended),
                                      ref.sediment, std::vector<std::int64_t>(rough.size(), 0));
  EXPECT_GT(s.changed, nx * ny / 2);
  EXPECT_LE(s.worst, 4);
  const auto water = model.water();
  double worst_water = 0;
  for (std::size_t k = 0; k < water.size(); ++k)
    worst_water = std::max(worst_water, std::fabs(water[k] - ref.water[k]));
  // a = h + w cancels in float at heights of 0.3 m: a few 1e-8 m per exchange, over three
  // iterations and four neighbours; a wrong rule differs by millimetres.
  EXPECT_LT(worst_water, 1e-5) << "m of water";
}

}  // namespace
}  // namespace runnel
