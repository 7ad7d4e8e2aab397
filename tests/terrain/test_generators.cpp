// SPDX-License-Identifier: MIT
// Generators: deterministic per seed, different across seeds, and the shapes match their geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "runnel/core/error.hpp"
#include "runnel/terrain/generators.hpp"

namespace runnel {
namespace {

class EveryGenerator : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryGenerator, SameSeedGivesIdenticalBits) {
  const Heightmap a = generate_terrain(GetParam(), 65, 49, 3.0, 42);
  const Heightmap b = generate_terrain(GetParam(), 65, 49, 3.0, 42);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.h.data(), b.h.data(), a.size() * sizeof(float)));
  for (float v : a.h) ASSERT_TRUE(std::isfinite(v));
  EXPECT_GT(a.max_height(), a.min_height()) << "a generator must not give a flat terrain";
  EXPECT_GE(a.min_height(), 0.0f);
}

std::vector<std::string> every_generator() {
  std::vector<std::string> names;
  for (const GeneratorSpec& g : generators()) names.push_back(g.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Generators, EveryGenerator, ::testing::ValuesIn(every_generator()),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n) c = c == '-' ? '_' : c;
                           return n;
                         });

class RandomGenerator : public ::testing::TestWithParam<std::string> {};

TEST_P(RandomGenerator, DifferentSeedsGiveDifferentTerrains) {
  const Heightmap a = generate_terrain(GetParam(), 65, 65, 1.0, 1);
  const Heightmap b = generate_terrain(GetParam(), 65, 65, 1.0, 2);
  std::size_t differing = 0;
  for (std::size_t k = 0; k < a.size(); ++k) differing += a.h[k] != b.h[k];
  EXPECT_GT(differing, a.size() / 2);
}

TEST_P(RandomGenerator, ReliefMatchesTheRequest) {
  const Heightmap t = generate_terrain(GetParam(), 129, 129, 2.0, 5, {{"relief", 0.1}});
  EXPECT_NEAR(t.min_height(), 0.0, 1e-4);
  EXPECT_NEAR(t.max_height(), 0.1 * 128 * 2.0, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Generators, RandomGenerator,
                         ::testing::Values("diamond-square", "fault", "fbm", "ridged", "midpoint",
                                           "successive-additions", "value-noise", "turbulence",
                                           "multifractal", "hybrid-multifractal", "hetero-terrain",
                                           "varying-hurst", "spectral", "circles", "rmp-voronoi",
                                           "rmp-graph"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n) c = c == '-' ? '_' : c;
                           return n;
                         });

TEST(Generators, PlaneHasTheRequestedSlope) {
  const Heightmap t =
      generate_terrain("plane", 33, 17, 2.0, 1, {{"slope", 30.0}, {"azimuth", 0.0}});
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i + 1 < t.nx; ++i) {
      ASSERT_NEAR((t.at(i + 1, j) - t.at(i, j)) / t.cell, std::tan(30.0 * M_PI / 180.0), 1e-4);
    }
  }
  EXPECT_NEAR(t.min_height(), 0.0, 1e-6);
}

TEST(Generators, ConeAndHemisphereHaveTheirGeometry) {
  const Heightmap cone =
      generate_terrain("cone", 101, 101, 1.0, 1, {{"relief", 0.3}, {"radius", 0.4}});
  EXPECT_NEAR(cone.at(50, 50), 30.0, 1e-4);  // apex: 0.3 × 100 m
  EXPECT_NEAR(cone.at(70, 50), 30.0 * (1 - 20.0 / 40.0), 1e-4);
  EXPECT_EQ(cone.at(0, 0), 0.0f);
  const Heightmap hemi = generate_terrain("hemisphere", 101, 101, 1.0, 1, {{"radius", 0.3}});
  EXPECT_NEAR(hemi.at(50, 50), 30.0, 1e-4);
  EXPECT_NEAR(hemi.at(50 + 18, 50 + 24), 0.0, 1e-3);  // 18² + 24² = 30²: on the rim
  EXPECT_NEAR(hemi.at(50 + 18, 50), std::sqrt(900.0 - 324.0), 1e-4);
}

TEST(Generators, ValleyAxisIsLowest) {
  const Heightmap t = generate_terrain("v-valley", 41, 21, 1.0, 1);
  for (int j = 0; j < t.ny; ++j) {
    for (int i = 0; i < t.nx; ++i) ASSERT_GE(t.at(i, j), t.at(20, j));
  }
  EXPECT_GT(t.at(20, 0), t.at(20, 20));  // the axis falls to the south
}

TEST(Generators, NonPowerOfTwoDiamondSquareIsCropped) {
  const Heightmap t = generate_terrain("diamond-square", 100, 60, 1.0, 3);
  EXPECT_EQ(t.nx, 100);
  EXPECT_EQ(t.ny, 60);
}

TEST(Generators, BadRequestsNameTheProblem) {
  auto message = [](auto f) {
    try {
      f();
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kUsage);
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { generate_terrain("volcano", 9, 9, 1, 1); }).find("volcano"),
            std::string::npos);
  EXPECT_NE(message([] {
              generate_terrain("fbm", 9, 9, 1, 1, {{"bogus", 1}});
            }).find("bogus"),
            std::string::npos);
  EXPECT_NE(message([] {
              generate_terrain("fbm", 9, 9, 1, 1, {{"octaves", 99}});
            }).find("octaves"),
            std::string::npos);
  EXPECT_NE(message([] { generate_terrain("fbm", 1, 9, 1, 1); }).find("--size"), std::string::npos);
  EXPECT_NE(message([] { generate_terrain("fbm", 9, 9, 0.0, 1); }).find("--cell"),
            std::string::npos);
}

}  // namespace
}  // namespace runnel
