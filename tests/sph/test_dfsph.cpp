// SPDX-License-Identifier: MIT
// The incompressible solver (sph.solver = "dfsph") on PoCL: its density pass against a brute-force
// sum in double precision, a lone drop's bounce, and bitwise reproducibility.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/sph_reference.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/validation/tank.hpp"
#include "runnel/validation/validation.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

Parameters dfsph_parameters() {
  Parameters p = default_parameters();
  p.set("sph.solver", std::string("dfsph"));
  p.set("sph.walls", false);
  return p;
}

// A jittered block of water on the floor (height 0) of a 2 m × 2 m terrain, away from its edges,
// and a few lone drops above it: bulk, free surface, the floor's volume map and drops.
HostParticles block_on_floor(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.01f, 0.01f), vel(-0.3f, 0.3f);
  HostParticles p;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 5; ++k)
        p.push(0.6f + 0.1f * i + jitter(rng), 0.05f + 0.1f * j + std::fabs(jitter(rng)),
               0.6f + 0.1f * k + jitter(rng), vel(rng), vel(rng), vel(rng), 1000.0f, 1e30f);
  for (int d = 0; d < 3; ++d)
    p.push(0.5f + 0.3f * d, 1.0f + 0.2f * d, 1.5f, vel(rng), -1.0f, vel(rng), 1000.0f, 1e30f);
  return p;
}

std::vector<float> read_buffer(const cl::Buffer& b, std::size_t n) {
  std::vector<float> v(n);
  if (n > 0) compute().queue().enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(float), v.data());
  return v;
}

TEST(Dfsph, DensityAndFactorMatchABruteForceSum) {
  const SphSettings s = SphSettings::from(dfsph_parameters(), 0.1, 2.0);
  ASSERT_TRUE(s.incompressible());
  const double floor_height = 0.0;  // flat_floor's
  SphSolver solver(compute(), s, flat_floor(20, 20, 0.1), 2.0);
  solver.add(block_on_floor(3));
  solver.prepare();  // sorts, then the density pass at the sorted positions
  ParticleStore& store = solver.particles();
  const HostParticles p = store.download();
  const std::size_t n = p.size();
  // The pass's factors in the store's first spare (dfsph.cpp), valid until the next sort.
  const std::vector<float> factor = read_buffer(store.spare(0), n);

  // The brute force: every pair, double precision, the floor a plane at floor_height (n = +y).
  // The factor is checked against the diagonal of the solves' system as the system itself defines
  // it, not against the kernel's closed form: the pressure acceleration of a unit κ at particle i
  // alone, a(e_i), and the rate of compression it causes at i, −Δ_i(a(e_i)).
  const double h = s.h, v0 = std::pow(s.spacing, 3) / s.lattice_sum();
  auto grad = [&](std::size_t i, std::size_t j, double g[3]) {
    const double x[3] = {double(p.f[kX][i]) - p.f[kX][j], double(p.f[kY][i]) - p.f[kY][j],
                         double(p.f[kZ][i]) - p.f[kZ][j]};
    const double r = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    const double f = r < 2 * h ? sph_reference::wendland_grad_factor(r, h) : 0.0;
    for (int c = 0; c < 3; ++c) g[c] = f * x[c];
    return r;
  };
  auto floor_integral = [&](std::size_t i) {
    return sph_reference::wall_integral(p.f[kY][i] - floor_height, h);
  };
  double worst_rho = 0, worst_factor = 0;
  int bulk = 0, lone = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double w = 0;
    int neighbours = 0;
    // a(e_i): at i, −V0 Σ_j ∇W_ij + 2 G n (the floor mirrors κ_i); at each neighbour j, −V0 ∇W_ji.
    double ai[3] = {0, 2 * floor_integral(i), 0};
    std::vector<std::array<double, 3>> aj(n, {0, 0, 0});
    for (std::size_t j = 0; j < n; ++j) {
      double g[3];
      const double r = grad(i, j, g);
      if (r >= 2 * h) continue;
      w += sph_reference::wendland_w(r, h);
      if (j == i) continue;
      ++neighbours;
      for (int c = 0; c < 3; ++c) ai[c] -= v0 * g[c], aj[j][c] = v0 * g[c];
    }
    // Δ_i(a) = V0 Σ_j (a_i − a_j)·∇W_ij − G a_i·n, and the part of it that is the pairs' own.
    double change = -floor_integral(i) * ai[1], pairs = 0;
    for (std::size_t j = 0; j < n; ++j) {
      double g[3];
      if (j == i || grad(i, j, g) >= 2 * h) continue;
      for (int c = 0; c < 3; ++c)
        change += v0 * (ai[c] - aj[j][c]) * g[c], pairs += v0 * aj[j][c] * g[c];
    }
    // The kernel keeps the diagonal positive: the part through a_i, g·(g − G n), at least 0.
    const double diagonal = std::max(-change - pairs, 0.0) + pairs;
    const double rho_hat = v0 * w + sph_reference::wall_volume(p.f[kY][i] - floor_height, h);
    const double expected_factor = diagonal > 1e-6 / (h * h) ? 1.0 / diagonal : 0.0;
    worst_rho = std::max(worst_rho, std::fabs(p.f[kRho][i] / s.rho0 - rho_hat));
    if (expected_factor > 0) {
      worst_factor =
          std::max(worst_factor, std::fabs(factor[i] - expected_factor) / expected_factor);
    } else {
      EXPECT_EQ(factor[i], 0.0f) << "particle " << i;
    }
    bulk += neighbours >= 20;
    lone += neighbours == 0;
  }
  EXPECT_GT(bulk, 20);  // the block has an inside
  EXPECT_EQ(lone, 3);   // and the drops are alone
  EXPECT_LT(worst_rho, 1e-5);
  EXPECT_LT(worst_factor, 1e-4);
}

// The memory a run is budgeted (sph_simulation.cpp) counts dfsph's per-particle buffers at the
// size the solver really allocates them: a whole number of particles' worth, at least one for
// every particle in the store.
TEST(Dfsph, PerParticleBuffersAreWhatTheBudgetCounts) {
  const SphSettings s = SphSettings::from(dfsph_parameters(), 0.1, 2.0);
  SphSolver solver(compute(), s, flat_floor(20, 20, 0.1), 2.0);
  EXPECT_EQ(solver.pressure_solver().allocated_bytes(), 0u);
  solver.add(block_on_floor(5));
  solver.prepare();
  const std::size_t bytes = solver.pressure_solver().allocated_bytes(),
                    each = solver.pressure_solver().bytes_per_particle();
  EXPECT_EQ(bytes % each, 0u);
  EXPECT_GE(bytes / each, solver.particles().size());
}

TEST(Dfsph, LoneDropNeverRisesAboveItsRelease) {
  // droplet_bounce's factor 0.0625 / 0.25 / 0.5 is sph.cfl_flow 0.1 / 0.4 (the default) / 0.8.
  for (double cfl : {0.0625, 0.25, 0.5}) {
    for (double e : {0.0, 1.0}) {
      const BounceResult b = droplet_bounce(compute(), dfsph_parameters(), cfl, e);
      EXPECT_LE(b.highest_after_landing, 1.01 * b.release_height) << "cfl " << cfl << ", e " << e;
      if (e == 1.0) {
        EXPECT_GE(b.highest_after_landing, 0.99 * b.release_height) << "cfl " << cfl;
      } else {
        EXPECT_NEAR(b.highest_after_landing, b.contact_height, 0.02 * b.contact_height)
            << "cfl " << cfl;
      }
    }
  }
}

TEST(Dfsph, StepsWithTheFlowNotTheSoundSpeed) {
  // The same drop under both solvers: dfsph's steps follow its speed, wcsph's the sound speed.
  Parameters p = dfsph_parameters();
  const BounceResult incompressible = droplet_bounce(compute(), p, 0.25, 0.0);
  p.set("sph.solver", std::string("wcsph"));
  const BounceResult weakly = droplet_bounce(compute(), p, 0.25, 0.0);
  EXPECT_LT(4 * incompressible.steps, weakly.steps);
}

// The next step is the flow's: cfl_flow · min(dx/|v|max, ½ sqrt(dx/|a|max)) with the non-pressure
// accelerations, the viscosity's limit, at most dt_max. Here the maxima are recomputed on the host
// from the particles each step leaves (the device reduces them in step_stats), as the drops speed
// up in their fall, and the rule applied to them independently.
TEST(Dfsph, EachStepFollowsTheFlowWithinDtMax) {
  for (const double dt_max : {0.0, 0.004}) {  // the default (0.05 s), and a cap the flow reaches
    Parameters p = dfsph_parameters();
    p.set("sph.dt_max", dt_max);
    const SphSettings s = SphSettings::from(p, 0.1, 2.0);
    SphSolver solver(compute(), s, flat_floor(20, 20, 0.1), 2.0);
    solver.add(block_on_floor(3));
    double smallest = 1e30, largest = 0;
    for (int k = 0; k < 12; ++k) {
      solver.step();
      double v2 = 0, a2 = 0;
      for (auto [field, most] : {std::pair{kVx, &v2}, std::pair{kAx, &a2}}) {
        std::array<std::vector<float>, 3> c;
        for (int k = 0; k < 3; ++k) c[k] = solver.particles().read_field(ParticleField(field + k));
        for (std::size_t i = 0; i < c[0].size(); ++i)
          *most = std::max(*most, double(c[0][i]) * c[0][i] + double(c[1][i]) * c[1][i] +
                                      double(c[2][i]) * c[2][i]);
      }
      const double nu = s.alpha_visc * s.c0 * s.h / 10.0;
      const double flow = s.cfl_flow * std::min(s.spacing / std::sqrt(v2),
                                                0.5 * std::sqrt(s.spacing / std::sqrt(a2)));
      const double expected = std::min({flow, 0.125 * s.h * s.h / nu, s.dt_max});
      EXPECT_NEAR(solver.dt(), expected, 1e-5 * expected) << "dt_max " << dt_max << ", step " << k;
      smallest = std::min(smallest, solver.dt());
      largest = std::max(largest, solver.dt());
    }
    if (dt_max > 0) {
      EXPECT_EQ(largest, dt_max) << "the cap binds where the flow would allow more";
    } else {
      EXPECT_LT(smallest, 0.8 * largest) << "the step changes with the flow";
    }
  }
}

TEST(Dfsph, RunsAreBitwiseReproducible) {
  const SphSettings s = SphSettings::from(dfsph_parameters(), 0.1, 2.0);
  auto run = [&] {
    SphSolver solver(compute(), s, flat_floor(20, 20, 0.1), 2.0);
    solver.add(block_on_floor(5));
    for (int k = 0; k < 15; ++k) solver.step();
    return solver.particles().download();
  };
  const HostParticles a = run(), b = run();
  ASSERT_EQ(a.size(), b.size());
  for (int f : {kX, kY, kZ, kVx, kVy, kVz, kRho}) {
    for (std::size_t i = 0; i < a.size(); ++i)
      ASSERT_EQ(std::memcmp(&a.f[f][i], &b.f[f][i], sizeof(float)), 0) << "field " << f << " " << i;
  }
}

}  // namespace
}  // namespace runnel
