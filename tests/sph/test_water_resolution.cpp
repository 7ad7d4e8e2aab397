// SPDX-License-Identifier: MIT
// How many particles' water a footprint holds (sph/water_resolution.hpp), measured on the solver's
// own water depth: a lone drop resting on the ground is one particle's water, a film that no level
// resolves; a sheet three particles deep holds the continuum depth of three layers; a drop in the
// air is not on the bed. Scattered films read the mean depth of the water they belong to, whatever
// the particles' size (water_depth_reference.hpp). And `runnel run` and `runnel compare`'s report
// say when unresolved films dominate.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/footprint.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/sph/water_depth_reference.hpp"
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
  const SphSettings sph = SphSettings::from(default_parameters(), kSpacing, 3.0);
  const Heightmap floor = flat_floor(kCells, kCells, kCell);
  SphSolver solver(compute(), sph, floor, 10.0);
  for (std::size_t i = 0; i < host.size(); ++i) host.id[i] = static_cast<std::uint32_t>(i);
  solver.add(host);
  for (int s = 0; s < steps; ++s) solver.step();
  ParticleStore& store = solver.particles();
  Measured m;
  const HostParticles p = store.download();
  m.x = p.f[kX];
  m.z = p.f[kZ];
  const std::vector<float> depth = store.read_field(kDepth);
  m.resolution =
      water_resolution({m.x, p.f[kY], m.z, depth, p.contacts}, floor, std::pow(kSpacing, 3),
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
  EXPECT_EQ(m.resolution.unresolved_share, 1.0);
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
  EXPECT_EQ(m.resolution.unresolved_share, 0.0);
  // Inside the sheet the water over a unit of area is three layers, 3·dx; a particle's own water on
  // its footprint is lone_particle_depth. Their ratio is what the median particle reads, since
  // most particles are farther than a footprint from the sheet's edges.
  const double own = lone_particle_depth(
      std::pow(kSpacing, 3), 12.25, 12.25, kCells + 1, kCells + 1, kCell,
      footprint_radius(SphSettings::from(default_parameters(), kSpacing, 3.0), kCell));
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

// Drops resting at random on a flat 128 m × 128 m floor of 2 m cells, as much water as a sheet
// `depth` deep; the mean D the solver gives the drops in the middle of the floor (away from its
// edges, where a footprint is cut), and the share of them that were films.
struct FilmReading {
  double mean_depth, film_share;
};
FilmReading scattered_films(double spacing, double depth) {
  const double cell = 2.0, side = 128.0;
  const SphSettings sph = SphSettings::from(default_parameters(), spacing, 3.0);
  const Heightmap floor = flat_floor(64, 64, cell);
  SphSolver solver(compute(), sph, floor, 10.0);
  const int n = static_cast<int>(std::lround(depth * side * side / std::pow(spacing, 3)));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, side);
  HostParticles host;
  for (int k = 0; k < n; ++k) {
    host.push(float(u(rng)), float(sph.contact_radius + sph.surface_eps), float(u(rng)), 0, 0, 0,
              1000.0f, 100.0f);
    host.id.back() = static_cast<std::uint32_t>(k);
  }
  solver.add(host);
  solver.step();
  ParticleStore& store = solver.particles();
  const std::vector<float> x = store.read_field(kX), z = store.read_field(kZ),
                           d = store.read_field(kDepth);
  const std::vector<DepthReading> reference = water_depth_reference(
      x, z, floor.nx, floor.ny, cell, footprint_radius(sph, cell), std::pow(spacing, 3));
  double sum = 0;
  int inside = 0, films = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (std::fabs(x[i] - 0.5 * side) > 0.25 * side || std::fabs(z[i] - 0.5 * side) > 0.25 * side)
      continue;
    sum += d[i];
    ++inside;
    films += reference[i].level > 0;
  }
  return {sum / inside, static_cast<double>(films) / inside};
}

TEST(WaterResolution, ScatteredFilmsReadTheDepthOfTheirSheetWhateverTheParticleSize) {
  // 2 cm of water as drops of 1 m³ is one drop to 50 m², far apart on footprints of 4 m: every
  // drop a film, whose own water alone would read 5–7 cm. As drops of 1/8 m³, 8 times as many.
  // The sheet they stand for is 2 cm deep either way (the k-nearest-neighbour estimate is
  // unbiased for scattered drops; measured 1.12 and 1.04 times the depth in a plain model).
  const double depth = 0.02;
  const FilmReading coarse = scattered_films(1.0, depth), fine = scattered_films(0.5, depth);
  EXPECT_GT(coarse.film_share, 0.95);
  EXPECT_GT(fine.film_share, 0.5);
  EXPECT_NEAR(coarse.mean_depth, depth, 0.2 * depth);
  EXPECT_NEAR(fine.mean_depth, depth, 0.2 * depth);
  EXPECT_NEAR(coarse.mean_depth / fine.mean_depth, 1.0, 0.15);
}

TEST(WaterResolution, RunCautionsWhenUnresolvedFilmsDominateAndOnlyThen) {
  test::ScratchDir dir;
  auto run = [&](const char* intensity, const char* out) {
    return test::run_cli({"run", test::source_dir() + "/data/scenarios/default.toml", "--set",
                          "terrain.size=33", "--set", std::string("rain.intensity=") + intensity,
                          "--set", "rain.lifespan=1e9", "--set", "erosion.morphological_factor=100",
                          "--set", "run.sim_time=10", "--out", dir.path(out)});
  };
  // 300 mm/h for 10 s is 0.8 mm of water: three or four drops of 1 m³ on the 64 m × 64 m terrain.
  const auto light = run("300", "light");
  ASSERT_EQ(light.exit_code, 0) << light.err;
  EXPECT_NE(light.err.find("caution: "), std::string::npos) << light.err;
  EXPECT_NE(light.err.find("\"Films\""), std::string::npos) << light.err;
  const std::string metrics = test::read_text(dir.path("light/metrics.json"));
  EXPECT_NE(metrics.find("\"water_resolution\""), std::string::npos);
  const auto heavy = run("60000", "heavy");
  ASSERT_EQ(heavy.exit_code, 0) << heavy.err;
  EXPECT_EQ(heavy.err.find("caution: "), std::string::npos) << heavy.err;
}

TEST(WaterResolution, CompareReportCarriesTheSphCautionBesideItsTable) {
  test::ScratchDir dir;
  const auto r = test::run_cli({"compare", "--models", "sph,thermal", "--set", "terrain.size=33",
                                "--set", "rain.intensity=300", "--set", "rain.lifespan=1e9",
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
