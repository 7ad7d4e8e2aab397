// SPDX-License-Identifier: MIT
// The water depth pass (cl/water_depth.cl) against a plain C++ computation of what it measures:
// every particle's volume counted on its footprint's vertices, depth_k = Σ_i V ŵ_ik / cell², and
// each particle reading D_i = Σ_k ŵ_ik depth_k back (footprint_weights, sph/footprint.hpp). The
// solver counts deep water (several particles to a tile of the hash) in runs of consecutive
// particles on a CPU (water_depth_scatter_runs), and sheets one particle a work-item: the first
// case is mostly a deep pool on cells 8 particles wide, so runs gather many footprints in one box
// and some outgrow it; the second is mostly drops scattered over the terrain, films that read their
// depth on coarser levels of the field (water_depth_reference.hpp, the plain computation of both).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/footprint.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/sph/water_depth_reference.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/surface.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

struct DepthCase {
  const char* name;
  int vertices;   // per side
  double cell;    // m
  int pool;       // particles per side of the pool (3 layers deep)
  int scattered;  // drops anywhere on the terrain
  int films;      // more particles than this must read a coarser level, or the levels go untested
};

void expect_depths_match_the_plain_sum(const DepthCase& c) {
  const double spacing = 0.5;
  const Heightmap terrain =
      generate_terrain("diamond-square", c.vertices, c.vertices, c.cell, 5, {{"relief", 0.05}});
  const SphSettings sph = SphSettings::from(default_parameters(), spacing, 5.0);
  SphSolver solver(compute(), sph, terrain, terrain.max_height() + 10.0);
  const double side = (c.vertices - 1) * c.cell;
  HostParticles host;
  auto drop = [&](double x, double lift, double z) {
    host.push(float(x), float(surface_height(terrain, x, z) + lift), float(z), 0, 0, 0,
              float(sph.rho0), 10.0f);
    host.id.back() = static_cast<std::uint32_t>(host.size() - 1);
  };
  for (int layer = 0; layer < 3; ++layer) {
    for (int a = 0; a < c.pool; ++a) {
      for (int b = 0; b < c.pool; ++b) {
        drop(0.3 * side + a * spacing, (0.5 + layer) * spacing, 0.3 * side + b * spacing);
      }
    }
  }
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < c.scattered; ++k) drop(side * u(rng), 2.0 * u(rng), side * u(rng));
  solver.add(host);
  solver.step();  // the depth is measured at the end of a step, where the particles now are

  const HostParticles p = solver.particles().download();
  ASSERT_EQ(p.size(), host.size()) << c.name;
  std::vector<float> measured(p.size());  // D is a per-step field, not part of the state
  compute().queue().enqueueReadBuffer(solver.particles().buffer(kDepth), CL_TRUE, 0,
                                      measured.size() * sizeof(float), measured.data());
  const double radius = footprint_radius(sph, c.cell), volume = std::pow(spacing, 3);
  const std::vector<DepthReading> reference =
      water_depth_reference(p.f[kX], p.f[kZ], terrain.nx, terrain.ny, c.cell, radius, volume);
  double worst = 0, sum = 0;
  int films = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double expected = reference[i].depth;
    const double error = std::fabs(measured[i] - expected) / expected;
    worst = std::max(worst, error);
    sum += error;
    films += reference[i].level > 0;
  }
  EXPECT_GT(films, c.films) << c.name;
  // The counts are whole micrometres of depth, shared out by rounding: far below these bounds.
  EXPECT_LT(worst, 2e-3) << c.name;
  EXPECT_LT(sum / p.size(), 2e-4) << c.name;
}

TEST(WaterDepthOracle, ParticlesFarSmallerThanTheCellsShareTheirVertices) {
  expect_depths_match_the_plain_sum({"cells of 8 spacings", 17, 4.0, 40, 300, 0});
}

TEST(WaterDepthOracle, ParticlesFarLargerThanTheCellsReachTheWidestFootprint) {
  // The footprint's radius is capped at 8 cells: 17 vertices along an axis, the largest box.
  expect_depths_match_the_plain_sum({"cells of a tenth of a spacing", 321, 0.05, 20, 30, 10});
}

TEST(WaterDepthOracle, ParticlesOfHalfACellAsInTheDefaultScenario) {
  expect_depths_match_the_plain_sum({"cells of 2 spacings", 65, 1.0, 24, 2000, 100});
}

}  // namespace
}  // namespace runnel
