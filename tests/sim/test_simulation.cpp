// SPDX-License-Identifier: MIT
// The whole rain-erosion model: exact mass balance with every term active, determinism, no particle
// below the surface on a rough terrain, and erosion concentrated where the water gathers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "runnel/models/parameter_table.hpp"
#include "runnel/models/sph_simulation.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/surface.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

// Heavy, short-lived rain with strong erosion on a small terrain: every mass-balance term moves.
Parameters busy_parameters() {
  Parameters p = default_parameters();
  p.set("rain.rate", 4000.0);
  p.set("rain.lifespan", 1.0);
  p.set("rain.max_particles", static_cast<std::int64_t>(3000));
  p.set("erosion.morphological_factor", 1000.0);
  p.set("thermal.interval", 0.005);
  p.set("thermal.talus_angle", 30.0);
  return p;
}

TEST(Simulation, MassBalanceClosesWithEveryTermActive) {
  // A bumpy slope falling east: water runs off the east edge (outflow) while rain keeps falling.
  const Heightmap terrain =
      generate_terrain("crooked", 49, 49, 1.0, 4, {{"slope", 25.0}, {"amplitude", 0.08}});
  Simulation sim(compute(), busy_parameters(), terrain);
  for (int k = 0; k < 1000; ++k) sim.step();
  const MassBalance m = sim.mass_balance();
  const SphCounters c = sim.counters();
  EXPECT_GT(m.eroded, 0.0);
  EXPECT_GT(m.deposited, 0.0);
  EXPECT_GT(m.suspended, 0.0);
  EXPECT_GT(m.outflow, 0.0);
  EXPECT_GT(c.evaporated_particles, 0);
  EXPECT_GT(c.outflow_particles, 0);
  EXPECT_LE(m.relative, 1e-6) << m.json().str();
  EXPECT_EQ(m.residual_quanta, 0) << m.json().str();
  // The terms add up: what left the terrain is suspended, flowed out, or was lost.
  EXPECT_NEAR(-m.terrain_change, m.suspended + m.outflow + m.lost, 1e-9 * m.eroded);
}

TEST(Simulation, NonConservingDepositFractionIsBookedAsLost) {
  Parameters p = busy_parameters();
  p.set("erosion.deposit_fraction", 0.1);  // Fritz 2016's hack
  const Heightmap terrain = generate_terrain("fbm", 49, 49, 1.0, 4, {{"relief", 0.25}});
  Simulation sim(compute(), p, terrain);
  for (int k = 0; k < 600; ++k) sim.step();
  const MassBalance m = sim.mass_balance();
  EXPECT_GT(m.lost, 0.0);
  EXPECT_EQ(m.residual_quanta, 0) << m.json().str();
}

// Every persistent field of two particle sets, bit for bit.
void expect_same_particles(const HostParticles& a, const HostParticles& b) {
  ASSERT_EQ(a.size(), b.size());
  for (int f = 0; f < kPersistentFieldCount; ++f) {
    const auto field = static_cast<ParticleField>(f);
    EXPECT_EQ(0, std::memcmp(a.data(field), b.data(field), a.size() * 4)) << f;
  }
}

TEST(Simulation, SameSeedGivesIdenticalTerrainAndParticles) {
  const Heightmap terrain = generate_terrain("fbm", 41, 41, 1.0, 2, {{"relief", 0.25}});
  std::vector<std::vector<std::int64_t>> heights;
  std::vector<HostParticles> particles;
  for (std::int64_t seed : {5, 5, 6}) {
    Parameters p = busy_parameters();
    p.set("run.seed", seed);
    Simulation sim(compute(), p, terrain);
    for (int k = 0; k < 300; ++k) sim.step();
    heights.push_back(sim.solver().terrain().download_fixed());
    particles.push_back(sim.solver().particles().download());
  }
  EXPECT_EQ(heights[0], heights[1]);
  expect_same_particles(particles[0], particles[1]);
  EXPECT_NE(heights[0], heights[2]) << "another seed must give another run";
}

// A GPU cuts the sort, the tile list and the step statistics into thousands of short runs and
// scans in a wide work-group; a CPU into a few long ones. The results must be the same bits. (The
// neighbour passes' tiles differ too, a GPU giving each particle its own work-item: that sums in
// another order, so both runs here keep this device's tiles; SphSolver.DirectPasses… checks the
// other.)
TEST(Simulation, TheSortAndStatisticsCutAsAGpuCutsThemGiveTheSameBits) {
  const Heightmap terrain = generate_terrain("fbm", 41, 41, 1.0, 2, {{"relief", 0.25}});
  std::vector<std::vector<std::int64_t>> heights;
  std::vector<HostParticles> particles;
  ASSERT_NE(test::compute_cut_the_other_way().wide(), compute().wide());
  for (ComputeContext* c : {&compute(), &test::compute_cut_the_other_way()}) {
    Simulation sim(*c, busy_parameters(), terrain);
    sim.solver().hash().set_tile(SpatialHash::device_tile(compute()));
    for (int k = 0; k < 300; ++k) sim.step();
    heights.push_back(sim.solver().terrain().download_fixed());
    particles.push_back(sim.solver().particles().download());
  }
  ASSERT_GT(particles[0].size(), 500u) << "enough particles for many runs of the GPU's cut";
  EXPECT_EQ(heights[0], heights[1]);
  expect_same_particles(particles[0], particles[1]);
}

// The GPU's neighbour passes (a work-item per particle, candidates beyond 2h skipped, the device's
// division), run here on the CPU with the rest of the GPU's cut, against this device's: the mass
// balance closes exactly, and the eroded and deposited volumes differ by no more than another
// seed's run differs from this device's (twice that, at least 1 % of the volume).
TEST(Simulation, AGpusNeighbourPassesConserveAndErodeAsThisDevicesDo) {
  const Heightmap terrain =
      generate_terrain("crooked", 49, 49, 1.0, 4, {{"slope", 25.0}, {"amplitude", 0.08}});
  std::vector<MassBalance> runs;
  for (int r = 0; r < 3; ++r) {
    Parameters p = busy_parameters();
    if (r == 2) p.set("run.seed", std::int64_t{77});
    ComputeContext& device = r == 1 ? test::compute_cut_the_other_way() : compute();
    Simulation sim(device, p, terrain);
    ASSERT_EQ(sim.solver().hash().tile_size(), SpatialHash::device_tile(device));
    for (int k = 0; k < 600; ++k) sim.step();
    runs.push_back(sim.mass_balance());
    EXPECT_EQ(runs.back().residual_quanta, 0) << r << ": " << runs.back().json().str();
  }
  const MassBalance &here = runs[0], &other = runs[1], &seed = runs[2];
  ASSERT_GT(here.eroded, 0.0);
  ASSERT_GT(here.deposited, 0.0);
  const double eroded_spread =
      std::max(2.0 * std::fabs(seed.eroded - here.eroded), 0.01 * here.eroded);
  const double deposited_spread =
      std::max(2.0 * std::fabs(seed.deposited - here.deposited), 0.01 * here.deposited);
  EXPECT_NEAR(other.eroded, here.eroded, eroded_spread) << "another seed: " << seed.eroded;
  EXPECT_NEAR(other.deposited, here.deposited, deposited_spread)
      << "another seed: " << seed.deposited;
}

TEST(Simulation, NoParticleBelowTheSurfaceAfterALongRunOnRoughTerrain) {
  const Heightmap rough =
      generate_terrain("diamond-square", 49, 49, 1.0, 8, {{"relief", 0.35}, {"roughness", 0.5}});
  Simulation sim(compute(), busy_parameters(), rough);
  for (int k = 0; k < 1500; ++k) sim.step();
  const Heightmap now = sim.terrain();
  const HostParticles p = sim.solver().particles().download();
  ASSERT_GT(p.size(), 100u);
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_GE(p.f[kY][i] - surface_height(now, p.f[kX][i], p.f[kZ][i]), -1e-4)
        << "particle " << p.id[i];
  }
}

// Mean eroded depth (m) on the valley axis (within 3 cells) and on the flanks.
std::pair<double, double> axis_and_flank_erosion(Simulation& sim) {
  const Heightmap now = sim.terrain();
  double axis = 0, flanks = 0;
  int axis_n = 0, flank_n = 0;
  for (int j = 0; j < now.ny; ++j) {
    for (int i = 0; i < now.nx; ++i) {
      const double eroded = std::max(0.0, double(sim.initial_terrain().at(i, j)) - now.at(i, j));
      if (std::abs(i - now.nx / 2) <= 3) {
        axis += eroded;
        ++axis_n;
      } else {
        flanks += eroded;
        ++flank_n;
      }
    }
  }
  return {axis / axis_n, flanks / flank_n};
}

TEST(Simulation, RainOnAValleyGathersOnItsAxisAndErodesIt) {
  // Rain on both flanks (10°) runs down to the axis (15°) and out at its foot: the water gathered
  // there spends far more power on the bed (ω = ρ g q S) than the sheets on the flanks, so the axis
  // erodes most. Particles of the cell's size keep the test quick.
  Parameters p = default_parameters();
  p.set("sph.spacing", 1.0);
  p.set("rain.rate", 40.0);
  p.set("rain.lifespan", 1000.0);
  p.set("erosion.morphological_factor", 200.0);
  p.set("thermal.interval", 0.0);
  const Heightmap valley =
      generate_terrain("v-valley", 49, 49, 1.0, 1, {{"side_slope", 10.0}, {"axis_slope", 15.0}});
  Simulation sim(compute(), p, valley);
  while (sim.time() < 30.0) sim.step();
  // Water gathers: the band of ±4 m is 1/6 of the width, where rain alone would keep 17 % of it.
  const HostParticles q = sim.solver().particles().download();
  ASSERT_GT(q.size(), 100u);
  std::size_t near_axis = 0;
  for (std::size_t i = 0; i < q.size(); ++i) near_axis += std::fabs(q.f[kX][i] - 24.0) <= 4.0;
  EXPECT_GT(static_cast<double>(near_axis) / q.size(), 0.34) << near_axis << " of " << q.size();
  // And erodes: deeper on the axis than on the flanks.
  const auto [axis, flanks] = axis_and_flank_erosion(sim);
  EXPECT_GT(axis, 1.5 * flanks) << "axis " << axis << " m, flanks " << flanks << " m";
  EXPECT_EQ(sim.mass_balance().residual_quanta, 0);
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

TEST(Rain, DiscRegionBudgetAndIntensity) {
  Parameters p = default_parameters();
  p.set("rain.region", std::string("disc"));
  p.set("rain.disc_x", 20.0);
  p.set("rain.disc_z", 15.0);
  p.set("rain.disc_radius", 6.0);
  p.set("rain.intensity", 3.6e7);  // 10 m/s of rain depth over the disc
  p.set("rain.max_particles", static_cast<std::int64_t>(300));
  p.set("rain.lifespan", 1000.0);
  p.set("rain.spawn_height", 5.0);
  p.set("thermal.interval", 0.0);
  const Heightmap flat = generate_terrain("plane", 41, 41, 1.0, 1, {{"slope", 0.0}});
  Simulation sim(compute(), p, flat);
  // intensity → rate: 10 m/s × π·6² m² / dx³ (dx = half the 1 m cell).
  EXPECT_NEAR(sim.rain().settings().rate, 10.0 * M_PI * 36.0 / 0.125, 1e-6);
  for (int k = 0; k < 100 && sim.particles() < 20; ++k) sim.step();
  const HostParticles first = sim.solver().particles().download();
  ASSERT_GT(first.size(), 0u);
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_LE(std::hypot(first.f[kX][i] - 20.0, first.f[kZ][i] - 15.0), 6.0 + 1e-3);
  }
  for (int k = 0; k < 400; ++k) sim.step();
  EXPECT_EQ(sim.particles(), 300u) << "the budget caps the particles alive";
  EXPECT_EQ(sim.rain().spawned(), 300u);
}

TEST(Erosion, AcidityModelErodesAFixedAmountPerContactAndConserves) {
  Parameters p = busy_parameters();
  p.set("erosion.model", std::string("acidity"));
  p.set("erosion.capacity_contacts", static_cast<std::int64_t>(3));
  p.set("erosion.acidity", 0.002);
  const Heightmap terrain = generate_terrain("crooked", 41, 41, 1.0, 2, {{"slope", 20.0}});
  Simulation sim(compute(), p, terrain);
  for (int k = 0; k < 400; ++k) sim.step();
  const MassBalance m = sim.mass_balance();
  EXPECT_GT(m.eroded, 0.0);
  EXPECT_EQ(m.residual_quanta, 0);
  // No particle erodes more than capacity_contacts events of acidity · cell².
  const HostParticles q = sim.solver().particles().download();
  const double quantum = sim.solver().terrain().volume_quantum();
  for (std::size_t i = 0; i < q.size(); ++i) {
    EXPECT_LE(q.contacts[i] & ~kTouchingFlag, 3u);  // the top bit is the contact state
    // Three events of acidity · cell², each rounded to whole quanta (stochastically: one more at
    // most).
    EXPECT_LE(q.sediment[i] * quantum, 3 * (0.002 * 1.0 + quantum) + 1e-9);
  }
}

}  // namespace
}  // namespace runnel
