// SPDX-License-Identifier: MIT
// The viewer's water surface at the particles' scale: the volume the particles stand for, a flat
// layer read as flat, and every vertex equal to a brute-force sum over all particles.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runnel/models/water_surface.hpp"
#include "runnel/terrain/surface.hpp"

namespace runnel {
namespace {

Heightmap sloping(int n, double cell) {
  Heightmap t(n, n, cell);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) t.at(i, j) = static_cast<float>(0.3 * i * cell + 0.1 * j * cell);
  return t;
}

WaterView scattered(int count, double extent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> where(-1.0f, static_cast<float>(extent) + 1.0f),
      load(0.0f, 0.1f), speed(-3.0f, 3.0f);
  WaterView v;
  for (int p = 0; p < count; ++p) {
    v.points.insert(v.points.end(), {where(rng), 1.0f, where(rng), load(rng)});
    v.point_velocity.insert(v.point_velocity.end(), {speed(rng), speed(rng)});
  }
  return v;
}

TEST(WaterSurface, ParticlesSpreadOnAGridOfTheirSpacingKeepingTheirVolume) {
  const Heightmap t = sloping(17, 2.0);
  const double spacing = 1.0;
  const WaterView v = scattered(500, 32.0, 3);  // some beyond the edges
  const WaterSurface s = particle_water_surface(t, v, spacing);
  EXPECT_EQ(s.nx, 33);
  EXPECT_EQ(s.ny, 33);
  EXPECT_DOUBLE_EQ(s.cell, 1.0);
  double volume = 0;
  for (float d : s.depth) volume += d * s.cell * s.cell;
  EXPECT_NEAR(volume, 500 * spacing * spacing * spacing, 1e-4);
  // The ground under the water is the terrain's mesh.
  EXPECT_FLOAT_EQ(s.ground[5 * s.nx + 7], static_cast<float>(surface_height(t, 7.0, 5.0)));
}

TEST(WaterSurface, AUniformLayerReadsAsAFlatSurfaceItsDepthDeep) {
  const Heightmap t(33, 33, 1.0f);
  const double spacing = 0.5;
  WaterView v;
  for (int layer = 0; layer < 3; ++layer)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        v.points.insert(v.points.end(), {static_cast<float>((i + 0.5) * spacing),
                                         static_cast<float>((layer + 0.5) * spacing),
                                         static_cast<float>((j + 0.5) * spacing), 0.0f});
  const WaterSurface s = particle_water_surface(t, v, spacing);
  ASSERT_EQ(s.nx, 65);
  float lo = 1e9f, hi = 0;
  for (int j = 8; j <= 56; ++j)  // the interior, away from the layer's edges
    for (int i = 8; i <= 56; ++i) {
      lo = std::min(lo, s.depth[static_cast<std::size_t>(j) * s.nx + i]);
      hi = std::max(hi, s.depth[static_cast<std::size_t>(j) * s.nx + i]);
    }
  EXPECT_NEAR(lo, 3 * spacing, 0.02 * 3 * spacing);
  EXPECT_NEAR(hi, 3 * spacing, 0.02 * 3 * spacing);
}

// Every vertex against a sum over every particle and, for each particle, over every vertex (its
// kernel's normalisation): no stencil, no neighbour lists.
TEST(WaterSurface, EachVertexIsTheKernelWeightedSumOverAllParticles) {
  const Heightmap t = sloping(9, 2.0);
  const double spacing = 1.0, radius = 2.0 * spacing, volume = 1.0;
  const WaterView v = scattered(60, 16.0, 11);
  const WaterSurface s = particle_water_surface(t, v, spacing);
  const auto kernel = [&](double dx, double dz) {
    const double q2 = (dx * dx + dz * dz) / (radius * radius);
    return q2 < 1 ? std::pow(1 - q2, 3) : 0.0;
  };
  const std::size_t n = static_cast<std::size_t>(s.nx) * s.ny;
  std::vector<double> water(n, 0.0), sediment(n, 0.0), flow_x(n, 0.0);
  for (std::size_t p = 0; p < v.points.size() / 4; ++p) {
    const double x = v.points[4 * p], z = v.points[4 * p + 2];
    double total = 0;
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) total += kernel(i * s.cell - x, j * s.cell - z);
    ASSERT_GT(total, 0) << "the scattered particles lie within a kernel of the grid";
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) {
        const std::size_t k = static_cast<std::size_t>(j) * s.nx + i;
        const double share = volume * kernel(i * s.cell - x, j * s.cell - z) / total;
        water[k] += share;
        sediment[k] += share * v.points[4 * p + 3];
        flow_x[k] += share * v.point_velocity[2 * p];
      }
  }
  for (std::size_t k = 0; k < n; ++k) {
    ASSERT_NEAR(s.depth[k], water[k] / (s.cell * s.cell), 1e-5) << "vertex " << k;
    if (water[k] > 1e-6) {
      ASSERT_NEAR(s.load[k], sediment[k] / water[k], 1e-5) << "vertex " << k;
      ASSERT_NEAR(s.velocity[2 * k], flow_x[k] / water[k], 1e-4) << "vertex " << k;
    }
  }
}

}  // namespace
}  // namespace runnel
