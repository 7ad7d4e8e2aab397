// SPDX-License-Identifier: MIT
// How many particles' water a footprint holds (sph/water_resolution.hpp), measured on the solver's
// own water depth: a lone drop resting on the ground is one particle's water, a film of its own; a
// sheet three particles deep holds the continuum depth of three layers, far more than two
// particles'; a drop in the air is not on the bed. And `runnel run` and `runnel compare`'s report
// say when films dominate.
#include <gtest/gtest.h>

#include <cmath>

#include "runnel/sph/footprint.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/sph/water_resolution.hpp"
#include "runnel/validation/tank.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

constexpr double kSpacing = 0.5, kCell = 1.0;
constexpr int kCells = 24;

struct Measured {
  WaterResolution resolution;
  std::vector<float> x, z;
};

// `host` on a flat 24 m × 24 m floor of 1 m cells after `steps` steps, measured as `runnel run`
// measures it at the end of a run.
Measured settle_and_measure(HostParticles host, int steps) {
  const SphSettings sph = SphSettings::from(Parameters(), kSpacing, 3.0);
  const Heightmap floor = flat_floor(kCells, kCells, kCell);
  SphSolver solver(compute(), sph, floor, 10.0);
  for (std::size_t i = 0; i < host.size(); ++i) host.id[i] = static_cast<std::uint32_t>(i);
  solver.add(host);
  for (int s = 0; s < steps; ++s) solver.step();
  ParticleStore& store = solver.particles();
  Measured m;
  m.x = store.read_field(kX);
  m.z = store.read_field(kZ);
  const std::vector<float> y = store.read_field(kY), depth = store.read_field(kDepth);
  m.resolution = water_resolution({m.x, y, m.z, depth}, floor, std::pow(kSpacing, 3),
                                  footprint_radius(sph, kCell), sph.contact_radius);
  return m;
}

HostParticles drop_at(double x, double y, double z) {
  HostParticles host;
  host.push(float(x), float(y), float(z), 0, 0, 0, 1000.0f, 100.0f);
  return host;
}

TEST(WaterResolution, ALoneDropRestingOnTheGroundHoldsOneParticlesWater) {
  const Measured m = settle_and_measure(drop_at(11.3, 0.5 * kSpacing, 12.6), 200);
  ASSERT_EQ(m.resolution.bed_particles, 1);
  // The depth pass counts in whole micrometres; the drop's own depth is about 10 mm.
  EXPECT_NEAR(m.resolution.median_particles_per_footprint, 1.0, 0.01);
  EXPECT_EQ(m.resolution.film_share, 1.0);
}

TEST(WaterResolution, ASheetThreeParticlesDeepHoldsTheContinuumDepthOfThreeLayers) {
  HostParticles host;
  const int side = 28;  // 14 m of the 24 m floor, from 5 m on
  for (int layer = 0; layer < 3; ++layer)
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b)
        host.push(float(5.0 + (a + 0.5) * kSpacing), float((layer + 0.5) * kSpacing),
                  float(5.0 + (b + 0.5) * kSpacing), 0, 0, 0, 1000.0f, 100.0f);
  const Measured m = settle_and_measure(host, 1);
  // The top layer along the edges stands above the shallower water there; the rest is on the bed.
  EXPECT_GT(m.resolution.bed_particles, 2 * side * side + (side - 8) * (side - 8));
  EXPECT_LE(m.resolution.bed_particles, 3 * side * side);
  EXPECT_EQ(m.resolution.film_share, 0.0);
  // Inside the sheet the water over a unit of area is three layers, 3·dx; a particle's own water on
  // its footprint is lone_particle_depth. Their ratio is what the median particle reads, since
  // most particles are farther than a footprint from the sheet's edges.
  const double own =
      lone_particle_depth(std::pow(kSpacing, 3), 12.25, 12.25, kCells + 1, kCells + 1, kCell,
                          footprint_radius(SphSettings::from(Parameters(), kSpacing, 3.0), kCell));
  const double continuum = 3.0 * kSpacing / own;
  EXPECT_NEAR(m.resolution.median_particles_per_footprint, continuum, 0.1 * continuum)
      << "own depth " << own << " m";
}

TEST(WaterResolution, ADropInTheAirIsNotOnTheBed) {
  const Measured m = settle_and_measure(drop_at(11.3, 3.0, 12.6), 1);
  EXPECT_EQ(m.resolution.bed_particles, 0);
  EXPECT_EQ(m.resolution.film_share, 0.0);
  EXPECT_EQ(m.resolution.median_particles_per_footprint, 0.0);
}

TEST(WaterResolution, RunCautionsWhenFilmsDominateAndOnlyThen) {
  test::ScratchDir dir;
  auto run = [&](const char* intensity, const char* out) {
    return test::run_cli({"run", test::source_dir() + "/data/scenarios/default.toml", "--set",
                          "terrain.size=33", "--set", std::string("rain.intensity=") + intensity,
                          "--set", "rain.lifespan=1e9", "--set", "erosion.morphological_factor=100",
                          "--set", "run.sim_time=10", "--out", dir.path(out)});
  };
  const auto light = run("2000", "light");
  ASSERT_EQ(light.exit_code, 0) << light.err;
  EXPECT_NE(light.err.find("caution: "), std::string::npos) << light.err;
  EXPECT_NE(light.err.find("Unresolved films"), std::string::npos) << light.err;
  const std::string metrics = test::read_text(dir.path("light/metrics.json"));
  EXPECT_NE(metrics.find("\"water_resolution\""), std::string::npos);
  const auto heavy = run("60000", "heavy");
  ASSERT_EQ(heavy.exit_code, 0) << heavy.err;
  EXPECT_EQ(heavy.err.find("caution: "), std::string::npos) << heavy.err;
}

TEST(WaterResolution, CompareReportCarriesTheSphCautionBesideItsTable) {
  test::ScratchDir dir;
  const auto r = test::run_cli({"compare", "--models", "sph,thermal", "--set", "terrain.size=33",
                                "--set", "rain.intensity=2000", "--set", "rain.lifespan=1e9",
                                "--set", "erosion.morphological_factor=100", "--set",
                                "run.sim_time=10", "--out", dir.path("cmp")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string report = test::read_text(dir.path("cmp/report.md"));
  EXPECT_NE(report.find("Cautions:\n\n- sph: "), std::string::npos) << report;
  EXPECT_EQ(report.find("- thermal: "), report.find("- thermal: the scenario"))
      << "thermal has no caution, only its budget line:\n"
      << report;
}

}  // namespace
}  // namespace runnel
