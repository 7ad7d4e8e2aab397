// SPDX-License-Identifier: MIT
// The distance from a point to the terrain's triangle mesh, and the water's surface over the wet
// vertices, against dense samples of the surface.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/surface.hpp"

namespace runnel {
namespace {

// The nearest of the surface points sampled every `step` along x and z around the point: an upper
// bound on the distance, above it by at most the sampling's reach on the steepest face.
double sampled_distance(const Heightmap& t, double x, double y, double z, double reach,
                        double step) {
  double nearest = std::numeric_limits<double>::infinity();
  for (double sz = z - reach; sz <= z + reach; sz += step)
    for (double sx = x - reach; sx <= x + reach; sx += step) {
      if (sx < 0 || sz < 0 || sx > (t.nx - 1) * t.cell || sz > (t.ny - 1) * t.cell) continue;
      const double dy = y - surface_height(t, sx, sz);
      nearest = std::min(nearest, std::sqrt((x - sx) * (x - sx) + dy * dy + (z - sz) * (z - sz)));
    }
  return nearest;
}

TEST(SurfaceDistance, IsTheNearestPointOfTheTrianglesOnARoughTerrain) {
  const Heightmap t = generate_terrain("fbm", 17, 17, 0.1, 5, {{"relief", 0.6}});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.2, 1.4), above(0.0, 0.15);
  const double reach = 0.2, step = 0.001;
  int tested = 0;
  for (int k = 0; k < 60; ++k) {
    const double x = u(rng), z = u(rng), y = surface_height(t, x, z) + above(rng);
    const double exact = distance_to_surface(t, x, y, z, reach);
    const double sampled = sampled_distance(t, x, y, z, reach, step);
    if (sampled > 0.9 * reach) continue;  // the search may stop at its reach
    ++tested;
    // Sampling only overestimates, by less than a sample's spacing over the steepest slope.
    ASSERT_LE(exact, sampled + 1e-9) << "at (" << x << ", " << y << ", " << z << ")";
    ASSERT_GE(exact, sampled - 0.01) << "at (" << x << ", " << y << ", " << z << ")";
    // And the vertical gap bounds it from above.
    ASSERT_LE(exact, y - surface_height(t, x, z) + 1e-9);
  }
  EXPECT_GT(tested, 40);
}

TEST(SurfaceDistance, BesideAVerticalishWallIsTheGapToTheWallNotTheFloor) {
  // A floor at 0 and a wall rising 1 m over one 0.1 m cell (from x = 0.1 to 0.2, falling east):
  // a point 0.05 m up and 0.03 m east of the wall's foot is nearer the face than the floor.
  Heightmap box(9, 3, 0.1, 0.0f);
  for (int j = 0; j < 3; ++j) box.at(0, j) = box.at(1, j) = 1.0f;
  const double x = 0.23, y = 0.05, z = 0.1;
  // The face's plane through (0.2, 0, ·) and (0.1, 1, ·): 10 (x − 0.2) + y = 0, normal (10,
  // 1)/√101.
  const double to_face = (10 * (x - 0.2) + y) / std::sqrt(101.0);
  EXPECT_NEAR(distance_to_surface(box, x, y, z, 0.2), std::min(to_face, y), 1e-12);
  EXPECT_LT(to_face, y);
  EXPECT_GE(distance_to_surface(box, 0.8, 0.5, 0.1, 0.2), 0.2) << "nothing within reach";
}

TEST(WetSurface, IsALakesLevelUpToItsBankAndAbsentOverDryTriangles) {
  // A bank rising from 0 at x = 0.2 to 1 at x = 0.1, a lake 0.5 deep east of it: over the bank's
  // face the water's surface is the lake's, where bed + interpolated depth would climb to 1.
  Heightmap bank(5, 3, 0.1, 0.0f);
  std::vector<float> depth(bank.size(), 0.5f);
  for (int j = 0; j < 3; ++j) {
    bank.at(0, j) = bank.at(1, j) = 1.0f;
    depth[j * 5 + 0] = depth[j * 5 + 1] = 0.0f;
  }
  for (double x : {0.11, 0.15, 0.19, 0.25, 0.39})
    EXPECT_DOUBLE_EQ(wet_surface_height(bank, depth, x, 0.07), 0.5) << "at x = " << x;
  EXPECT_EQ(wet_surface_height(bank, depth, 0.05, 0.07), -std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace runnel
