// SPDX-License-Identifier: MIT
// rain_emit against its plain C++ oracle (rain_reference): every region, on a rough terrain where
// the spawn height and the contact surface both decide the drop's height.
#include <gtest/gtest.h>

#include <cmath>

#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/rain_emitter.hpp"
#include "runnel/sph/rain_reference.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/surface.hpp"
#include "runnel/validation/tank.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

TEST(RainOracle, EmittedDropsMatchThePlainCppReferenceInEveryRegion) {
  const Heightmap rough = generate_terrain("diamond-square", 33, 29, 1.0, 4, {{"relief", 0.3}});
  for (const char* region : {"terrain", "rectangle", "disc"}) {
    Parameters p = default_parameters();
    p.set("rain.region", std::string(region));
    p.set("rain.rect_x0", 3.0), p.set("rain.rect_x1", 20.0);
    p.set("rain.rect_z0", 5.0), p.set("rain.rect_z1", 26.0);
    p.set("rain.disc_x", 14.0), p.set("rain.disc_z", 12.0), p.set("rain.disc_radius", 9.0);
    p.set("rain.rate", 20000.0);
    p.set("rain.spawn_height", 0.3);  // below the contact surface on the steepest slopes
    p.set("rain.speed", 1.5);
    const SphSettings sph = SphSettings::from(p, 0.5, 5.0);
    SphSolver solver(compute(), sph, rough, 40.0);
    const RainSettings settings = RainSettings::from(p, solver.terrain(), sph.spacing, 5.0);
    const std::uint64_t seed = 99;
    RainEmitter emitter(compute(), settings, seed, float(sph.rho0));
    emitter.emit(solver, 0.01);  // 200 drops: the first counters
    const std::size_t second = emitter.emit(solver, 0.0125);
    const HostParticles drops = solver.particles().download();
    ASSERT_EQ(drops.size(), 200u + second);
    const auto reference = rain_reference::emit(settings, sph.contact_radius, sph.surface_eps,
                                                rough, seed, 0, drops.size());
    double worst_xz = 0, worst_y = 0, worst_life = 0;
    int lifted = 0;
    for (std::size_t k = 0; k < drops.size(); ++k) {
      worst_xz = std::max({worst_xz, std::fabs(drops.f[kX][k] - reference[k].x),
                           std::fabs(drops.f[kZ][k] - reference[k].z)});
      worst_y = std::max(worst_y, std::fabs(drops.f[kY][k] - reference[k].y));
      worst_life = std::max(worst_life, std::fabs(drops.f[kLifespan][k] - reference[k].lifespan));
      lifted += reference[k].y > surface_height(rough, reference[k].x, reference[k].z) + 0.3 + 1e-4;
      EXPECT_EQ(drops.id[k], k);
      EXPECT_EQ(drops.f[kVy][k], -1.5f);
    }
    EXPECT_LT(worst_xz, 1e-4) << region << ": m, float against double over 30 m";
    EXPECT_LT(worst_y, 1e-4) << region;
    EXPECT_LT(worst_life, 1e-3 * settings.lifespan) << region;
    EXPECT_GT(lifted, 0) << region << ": some drops are held up by the contact surface";
  }
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// dfsph's long steps: each drop falls from its own time within the step (the k-th of count equal
// shares) to the step's end, under gravity; the oracle integrates the same fall in double.
TEST(RainOracle, IncompressibleStepsSpreadTheDropsOverTheStep) {
  const Heightmap rough = generate_terrain("diamond-square", 33, 29, 1.0, 4, {{"relief", 0.3}});
  Parameters p = default_parameters();
  p.set("sph.solver", std::string("dfsph"));
  p.set("rain.rate", 20000.0);
  p.set("rain.spawn_height", 3.0);  // above the contact surface everywhere
  p.set("rain.speed", 1.5);
  const SphSettings sph = SphSettings::from(p, 0.5, 5.0);
  SphSolver solver(compute(), sph, rough, 40.0);
  const RainSettings settings = RainSettings::from(p, solver.terrain(), sph.spacing, 5.0);
  RainEmitter emitter(compute(), settings, 7, float(sph.rho0));
  const double dt = 0.04;
  const std::size_t count = emitter.emit(solver, dt);
  ASSERT_EQ(count, 800u);
  const HostParticles drops = solver.particles().download();
  const auto reference = rain_reference::emit(settings, sph.contact_radius, sph.surface_eps, rough,
                                              7, 0, count, dt, sph.gravity);
  double worst_y = 0, worst_vy = 0, worst_age = 0;
  for (std::size_t k = 0; k < count; ++k) {
    worst_y = std::max(worst_y, std::fabs(drops.f[kY][k] - reference[k].y));
    worst_vy = std::max(worst_vy, std::fabs(drops.f[kVy][k] - reference[k].vy));
    worst_age = std::max(worst_age, std::fabs(drops.f[kAge][k] - reference[k].age));
  }
  EXPECT_LT(worst_y, 1e-4);
  EXPECT_LT(worst_vy, 1e-5);
  EXPECT_LT(worst_age, 1e-7);
  // The first drop fell for almost the whole step, the last for almost none.
  EXPECT_NEAR(reference.front().age, dt, dt / count);
  EXPECT_NEAR(reference.back().age, 0.0, dt / count);
  EXPECT_LT(drops.f[kVy].front(), -1.5f - 0.9f * float(sph.gravity * dt));
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// rain.above_water: over a pool the drops appear the spawn height above its surface, not inside
// it. The pool is a block 4 particles deep on a flat floor; its depth field (water volume over the
// cell area) is 4 dx inside it, so a drop over its middle appears 4 dx + spawn height above the
// floor, and everywhere the kernel's height is the oracle's from the depth field the pass measured.
TEST(RainOracle, AboveWaterDropsAppearAboveAPoolsSurface) {
  const Heightmap floor = flat_floor(24, 24, 0.2);
  Parameters p = default_parameters();
  p.set("rain.rate", 20000.0);
  p.set("rain.above_water", true);
  p.set("rain.spawn_height", 0.1);
  const double dx = 0.1;
  const SphSettings sph = SphSettings::from(p, dx, 2.0);
  SphSolver solver(compute(), sph, floor, 3.0);
  HostParticles pool;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 20; ++k)
        pool.push(1.45f + 0.1f * i, 0.05f + 0.1f * j, 1.45f + 0.1f * k, 0, 0, 0, 1000.0f, 1e30f);
  solver.add(pool);
  solver.prepare();  // measures the depth field
  const std::size_t vertices = static_cast<std::size_t>(floor.nx) * floor.ny;
  std::vector<cl_long> counts(vertices);
  compute().queue().enqueueReadBuffer(solver.water_field(), CL_TRUE, 0, vertices * sizeof(cl_long),
                                      counts.data());
  std::vector<double> depth(vertices);
  for (std::size_t v = 0; v < vertices; ++v) depth[v] = 1e-6 * static_cast<double>(counts[v]);

  const RainSettings settings = RainSettings::from(p, solver.terrain(), sph.spacing, 2.0);
  RainEmitter emitter(compute(), settings, 11, float(sph.rho0));
  const std::size_t count = emitter.emit(solver, 0.02);
  ASSERT_EQ(count, 400u);
  const HostParticles all = solver.particles().download();
  const auto reference = rain_reference::emit(settings, sph.contact_radius, sph.surface_eps, floor,
                                              11, 0, count, 0.0, 0.0, depth);
  double worst_y = 0;
  int over_the_middle = 0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all.id[i] < pool.size()) continue;  // the pool's own particles
    const std::size_t slot = all.id[i] - pool.size();
    ASSERT_LT(slot, count);
    worst_y = std::max(worst_y, std::fabs(all.f[kY][i] - reference[slot].y));
    const double x = all.f[kX][i], z = all.f[kZ][i];
    if (x > 2.0 && x < 3.0 && z > 2.0 && z < 3.0) {
      EXPECT_NEAR(all.f[kY][i], 4 * dx + 0.1, 0.1 * dx) << "a drop over the pool's middle";
      ++over_the_middle;
    }
    ++k;
  }
  EXPECT_EQ(k, count);
  EXPECT_GT(over_the_middle, 0);
  EXPECT_LT(worst_y, 1e-4);
}

}  // namespace
}  // namespace runnel
