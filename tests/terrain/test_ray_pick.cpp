// SPDX-License-Identifier: MIT
// Cursor picking on the terrain: rays from above hit the surface where the mesh is.
#include <gtest/gtest.h>

#include <random>

#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/ray_pick.hpp"
#include "runnel/terrain/surface.hpp"

namespace runnel {
namespace {

TEST(RayPick, HitsLieOnTheSurfaceAlongTheRay) {
  const Heightmap t = generate_terrain("fbm", 65, 49, 2.0, 3, {{"relief", 0.2}});
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0;
  for (int k = 0; k < 500; ++k) {
    // From a camera above and beside the terrain, aimed at a random point of it.
    const double o[3] = {-40.0 + 200 * u(rng), 80.0 + 40 * u(rng), -40.0 + 170 * u(rng)};
    const double target[3] = {128 * u(rng), 0.0, 96 * u(rng)};
    const double d[3] = {target[0] - o[0], surface_height(t, target[0], target[2]) - o[1],
                         target[2] - o[2]};
    const auto hit = pick_terrain(t, o, d);
    if (!hit) continue;
    ++hits;
    ASSERT_NEAR(hit->y, surface_height(t, hit->x, hit->z), 1e-6);
    ASSERT_LE(hit->t, 1.0 + 1e-9) << "the ray is aimed at a surface point: it cannot pass it";
    // Nothing above the surface before the hit: sample the ray.
    for (double s = 0.0; s < hit->t; s += hit->t / 64) {
      const double x = o[0] + s * d[0], y = o[1] + s * d[1], z = o[2] + s * d[2];
      if (x < 0 || z < 0 || x > 128 || z > 96) continue;
      ASSERT_GE(y, surface_height(t, x, z) - 1e-6);
    }
  }
  EXPECT_GT(hits, 400);
  const double up[3] = {10, 1, 10}, away[3] = {0, 1, 0};
  EXPECT_FALSE(pick_terrain(t, up, away)) << "a ray pointing up misses";
}

}  // namespace
}  // namespace runnel
