// SPDX-License-Identifier: MIT
// Standing water at t = 0 ([[water.bodies]], water.depth) and gauges ([[probes]]): where the water
// lies, that a lake at rest stays at rest, that a closed box keeps its water, what a gauge reads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "runnel/core/parameters_toml.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/pipe_model.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sph/standing_water_particles.hpp"
#include "runnel/terrain/probes.hpp"
#include "runnel/terrain/standing_water.hpp"
#include "runnel/terrain/surface.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

// A terrain whose height is a given function of the world position (x east, z south).
template <class F>
Heightmap terrain_of(int n, double cell, F height) {
  Heightmap t(n, n, cell);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) t.at(i, j) = static_cast<float>(height(i * cell, j * cell));
  // The raster's lower-left corner half a cell outside the first vertex: vertex (i, j) stands at
  // map (i·cell, (n − 1 − j)·cell), its pixel's centre.
  t.origin_x = t.origin_z = -0.5 * cell;
  return t;
}

Parameters with_scenario(const std::string& toml) {
  Parameters p = default_parameters();
  read_parameters_toml(p, toml, "test");
  return p;
}

TEST(StandingWater, ABodyFillsTheTerrainBelowItsLevelInsideItsRectangleInMapMetres) {
  // A ramp rising 0.1 m a metre to the east, georeferenced at (1000, 2000); the body covers the
  // western half and the three northern rows (map y grows to the north, rows to the south).
  Heightmap t = terrain_of(11, 1.0, [](double x, double) { return 0.1 * x; });
  t.origin_x = 1000 - 0.5;  // vertex (0, 10) at map (1000, 2000)
  t.origin_z = 2000 - 0.5;
  const Parameters p =
      with_scenario("[[water.bodies]]\nx0 = 1000\nx1 = 1005\ny0 = 2008\ny1 = 2010\nlevel = 0.35\n");
  const std::vector<float> depth = initial_water_depth(p, t);
  double volume = 0;
  for (int j = 0; j < 11; ++j)
    for (int i = 0; i < 11; ++i) {
      const double expected = (j <= 2 && i <= 5) ? std::max(0.0, 0.35 - 0.1 * i) : 0.0;
      EXPECT_NEAR(depth[j * 11 + i], expected, 1e-6) << "vertex " << i << ", row " << j;
      volume += expected;
    }
  EXPECT_NEAR(water_volume(depth, t), volume, 1e-5);
}

TEST(StandingWater, ALakeAtRestStaysAtRestAndAGaugeReadsItsLevel) {
  // A bowl holding a lake up to 2 m, closed edges, no rain, no evaporation: neither of the pipe
  // model's fluxes may move it (a lake at rest), and a gauge in it reads the level as the water
  // surface. (Cells of 1 m: Mei's pipes carry waves at sqrt(g A / l), docs/models.md, "pipe".)
  const Heightmap bowl = terrain_of(33, 1.0, [](double x, double z) {
    return 0.02 * ((x - 16) * (x - 16) + (z - 16) * (z - 16));
  });
  for (const char* flux : {"pipes", "local-inertial", "godunov"}) {
    Parameters p = with_scenario(
        std::string("[pipe]\nrain = 0\nevaporation = 0\nedges = \"closed\"\nflux = \"") + flux +
        "\"\n[[water.bodies]]\nx0 = 0\nx1 = 32\ny0 = 0\ny1 = 32\nlevel = 2\n"
        "[[probes]]\nname = \"middle\"\nx = 15.3\ny = 16.6\n");
    PipeModel model(compute(), p, bowl);
    const std::vector<float> start = model.depth();
    EXPECT_NEAR(model.initial_water_volume(), water_volume(start, bowl), 1e-9);
    EXPECT_GT(model.initial_water_volume(), 300.0);
    while (model.time() < 30.0) model.step();
    const std::vector<float> end = model.depth();
    for (std::size_t v = 0; v < end.size(); ++v) ASSERT_NEAR(end[v], start[v], 1e-4) << flux << v;
    const std::vector<Probe> probes = probes_of(p, bowl);
    ASSERT_EQ(probes.size(), 1u);
    const ProbeReading r = read_probe(model.terrain(), end, probes[0]);
    EXPECT_NEAR(r.surface, 2.0, 1e-4) << flux;
    EXPECT_NEAR(r.bed + r.depth, r.surface, 1e-12);
  }
}

TEST(StandingWater, AClosedBoxKeepsTheWaterOfItsDamBreak) {
  // Half a flat box filled 0.2 m deep and released: the water surges (without friction its front
  // runs at 2 sqrt(g h) = 2.8 m/s and meets the far wall within 1 s), and without rain, outflow or
  // evaporation its volume is the body's at every step.
  const Heightmap flat = terrain_of(41, 0.1, [](double, double) { return 0.0; });
  Parameters p = with_scenario(
      "[pipe]\nrain = 0\nevaporation = 0\nedges = \"closed\"\nmanning_n = 0\n"
      "[[water.bodies]]\nx0 = 0\nx1 = 1.95\ny0 = 0\ny1 = 4\nlevel = 0.2\n");
  PipeModel model(compute(), p, flat);
  const double initial = model.initial_water_volume();
  EXPECT_NEAR(initial, 20 * 41 * 0.2 * 0.01, 1e-6);  // columns 0..19, every row
  while (model.time() < 1.0) model.step();
  const std::vector<float> depth = model.depth();
  // Ritter's solution at the far wall (2.05 m past the dam) after 1 s: (2 c0 − x/t)² / 9g = 6.4 mm.
  EXPECT_GT(depth[40], 0.002f) << "the surge reached the far wall";
  EXPECT_NEAR(water_volume(depth, flat), initial, 1e-4 * initial);
}

TEST(StandingWater, SphParticlesFillEachColumnFromTheBedToTheWatersTop) {
  // A flat floor at 1 m under 1 m of water on its western half, particles 0.25 m apart: four
  // layers in every column of the half, at rest, none above the surface.
  const Heightmap flat = terrain_of(17, 0.5, [](double, double) { return 1.0; });
  std::vector<float> depth(flat.size(), 0.0f);
  for (int j = 0; j < 17; ++j)
    for (int i = 0; i <= 8; ++i) depth[j * 17 + i] = 1.0f;
  Parameters p = default_parameters();
  p.set("sph.spacing", 0.25);
  const SphSettings s = SphSettings::from(p, 0.25, 5.0);
  const HostParticles water = standing_water_particles(s, flat, depth);
  // Columns at x = (i + ½) · 0.25: the depth interpolates from 1 m at x = 4 to 0 at 4.5 m, and a
  // column holds ceil(d / 0.25 − ½) particles when it holds half a spacing at all.
  std::size_t expected = 0;
  for (int i = 0; i < 32; ++i) {
    const double x = (i + 0.5) * 0.25;
    const double d = x <= 4.0 ? 1.0 : std::max(0.0, 1.0 - (x - 4.0) / 0.5);
    if (d >= 0.125) expected += 32 * static_cast<std::size_t>(std::ceil(d / 0.25 - 0.5));
  }
  EXPECT_EQ(water.size(), expected);
  for (std::size_t k = 0; k < water.size(); ++k) {
    ASSERT_GT(water.f[kY][k], 1.0f);
    ASSERT_LT(water.f[kY][k], 2.0f);
    ASSERT_EQ(water.f[kVx][k], 0.0f);
    ASSERT_GE(water.f[kRho][k], static_cast<float>(s.rho0));  // hydrostatic: compressed below
  }
}

TEST(StandingWater, SphParticlesStayBelowALakesLevelAndClearOfItsSteepBanks) {
  // A pool 0.5 m deep in a box whose walls rise 1 m over one 0.1 m cell: over a wall's face the
  // water's top is the level (not bed + interpolated depth, which climbs the face), and no
  // particle starts nearer the face than the contact radius (the contact surface's raise is capped
  // on a face this steep). Distances by dense samples of the surface, 2 mm apart.
  Heightmap box(17, 17, 0.1, 0.0f);
  for (int j = 0; j < 17; ++j)
    for (int i = 0; i < 17; ++i)
      if (i < 2 || j < 2 || i > 14 || j > 14) box.at(i, j) = 1.0f;
  std::vector<float> depth(box.size());
  for (std::size_t k = 0; k < depth.size(); ++k) depth[k] = std::max(0.0f, 0.5f - box.h[k]);
  Parameters p = default_parameters();
  p.set("sph.spacing", 0.05);
  const SphSettings s = SphSettings::from(p, 0.05, 2.0);
  const HostParticles water = standing_water_particles(s, box, depth);
  const double r = s.contact_radius, step = 0.002;
  ASSERT_GT(water.size(), 1000u);
  int beside_a_face = 0;
  for (std::size_t k = 0; k < water.size(); ++k) {
    const double x = water.f[kX][k], y = water.f[kY][k], z = water.f[kZ][k];
    ASSERT_LT(y, 0.5) << "particle " << k << " at (" << x << ", " << y << ", " << z << ")";
    double nearest = 1e30;
    for (double sz = z - r; sz <= z + r; sz += step)
      for (double sx = x - r; sx <= x + r; sx += step) {
        const double dy = y - surface_height(box, sx, sz);
        nearest = std::min(nearest, (x - sx) * (x - sx) + dy * dy + (z - sz) * (z - sz));
      }
    // A sample 2 mm off the nearest point on a 10:1 face is at most ~1.5 mm farther.
    ASSERT_GE(std::sqrt(nearest), r - 0.0015)
        << "particle " << k << " at (" << x << ", " << y << ", " << z << ")";
    if (x < 0.2 + r || z < 0.2 + r) ++beside_a_face;
  }
  EXPECT_GT(beside_a_face, 100) << "the test looks at particles beside the walls";
}

TEST(StandingWater, AnSphLakeAtRestKeepsItsLevelAndVolume) {
  // The bowl's lake as SPH particles 1 m apart: the surface a gauge reads stays within half a
  // spacing of the level, and the particles hold the bowl's volume below it, π r² · 2 / 2 with
  // r = 10 m (314 m³), within the lattice's resolution.
  const Heightmap bowl = terrain_of(33, 1.0, [](double x, double z) {
    return 0.02 * ((x - 16) * (x - 16) + (z - 16) * (z - 16));
  });
  Parameters p = with_scenario(
      "[run]\nmodel = \"sph\"\n[rain]\nenabled = false\n[sph]\nspacing = 1.0\n"
      "[[water.bodies]]\nx0 = 0\nx1 = 32\ny0 = 0\ny1 = 32\nlevel = 2\n"
      "[[probes]]\nname = \"middle\"\nx = 16.2\ny = 15.7\n");
  std::unique_ptr<Model> model = make_model(compute(), p, bowl);
  const double analytic = M_PI * 100.0 * 2.0 / 2.0;
  EXPECT_NEAR(model->initial_water_volume(), analytic, 0.1 * analytic);
  const Probe gauge = probes_of(p, bowl).at(0);
  model->advance(2.0);
  const ProbeReading r =
      read_probe(model->terrain(), model->interaction().water_view().depth, gauge);
  EXPECT_NEAR(r.surface, 2.0, 0.5);
  EXPECT_EQ(model->mass_balance().residual_quanta, 0);
}

// Standing water against steep terrain walls (a box 1 m high around a 0.5 m pool) starts at rest:
// its first 10 weakly compressible steps stay within 3 % of ρ0 (sph.density_max = 1.03 stops a run
// beyond it). Stacked from the bed's own height, the columns at the walls' feet put particles
// within the walls' reach: 1,914 kg/m³ at the first step. (dfsph does not yet: docs/sph.md,
// "Standing water".)
TEST(StandingWater, SphWaterStartsAtRestBesideSteepWalls) {
  Heightmap box(33, 33, 0.1, 0.0f);
  for (int j = 0; j < 33; ++j)
    for (int i = 0; i < 33; ++i)
      if (i < 2 || j < 2 || i > 30 || j > 30) box.at(i, j) = 1.0f;
  box.origin_x = box.origin_z = -0.05;
  for (const char* solver : {"wcsph"}) {
    Parameters p =
        with_scenario(std::string("[run]\nmodel = \"sph\"\n[rain]\nenabled = false\n") +
                      "[sph]\nspacing = 0.05\ndensity_max = 1.03\nsolver = \"" + solver +
                      "\"\n[[water.bodies]]\nx0 = 0\nx1 = 4\ny0 = 0\ny1 = 4\n" + "level = 0.5\n");
    std::unique_ptr<Model> model = make_model(compute(), p, box);
    EXPECT_GT(model->initial_water_volume(), 0.5 * 2.7 * 2.7 * 0.8) << solver;
    for (int k = 0; k < 10; ++k) ASSERT_NO_THROW(model->step()) << solver << ", step " << k + 1;
  }
}

TEST(StandingWater, AResumedRunWithStandingWaterEqualsAnUninterruptedOne) {
  const Heightmap bowl = terrain_of(33, 1.0, [](double x, double z) {
    return 0.02 * ((x - 16) * (x - 16) + (z - 16) * (z - 16));
  });
  for (const char* model_name : {"pipe", "sph"}) {
    Parameters p =
        with_scenario(std::string("[run]\nmodel = \"") + model_name +
                      "\"\n[sph]\nspacing = 1.0\n"
                      "[[water.bodies]]\nx0 = 10\nx1 = 20\ny0 = 0\ny1 = 32\nlevel = 2\n");
    std::unique_ptr<Model> whole = make_model(compute(), p, bowl);
    for (int k = 0; k < 40; ++k) whole->step();
    std::unique_ptr<Model> first = make_model(compute(), p, bowl);
    for (int k = 0; k < 20; ++k) first->step();
    std::unique_ptr<Model> resumed = make_model_from_checkpoint(compute(), first->checkpoint());
    for (int k = 0; k < 20; ++k) resumed->step();
    EXPECT_EQ(resumed->terrain().h, whole->terrain().h) << model_name;
    EXPECT_EQ(resumed->interaction().water_view().depth, whole->interaction().water_view().depth)
        << model_name;
    EXPECT_EQ(resumed->initial_water_volume(), whole->initial_water_volume()) << model_name;
  }
}

TEST(Probes, ReadTheBedAndTheWaterOnTheTerrainsTriangles) {
  // On a plane the triangles' interpolation is exact: the gauge reads the plane's height at the
  // point, whichever triangle holds it, from map coordinates.
  Heightmap plane = terrain_of(9, 0.5, [](double x, double z) { return 2 + 0.5 * x + 0.25 * z; });
  plane.origin_x = 100 - 0.25;  // vertex (0, 8) at map (100, 200)
  plane.origin_z = 200 - 0.25;
  const std::vector<float> depth(plane.size(), 0.125f);
  std::ostringstream toml;
  toml << "[[probes]]\nname = \"a\"\nx = 101.3\ny = " << 200 + 8 * 0.5 - 2.6 << "\n"
       << "[[probes]]\nname = \"b\"\nx = 103.9\ny = 200.2\n";
  const std::vector<Probe> probes = probes_of(with_scenario(toml.str()), plane);
  ASSERT_EQ(probes.size(), 2u);
  const ProbeReading a = read_probe(plane, depth, probes[0]);
  EXPECT_NEAR(a.bed, 2 + 0.5 * 1.3 + 0.25 * 2.6, 1e-5);
  EXPECT_NEAR(a.depth, 0.125, 1e-6);
  EXPECT_NEAR(a.surface, a.bed + 0.125, 1e-5);
  const ProbeReading b = read_probe(plane, depth, probes[1]);
  EXPECT_NEAR(b.bed, 2 + 0.5 * 3.9 + 0.25 * (4 - 0.2), 1e-5);
}

TEST(Probes, RecordOnTheRunsClockAtWholeMultiplesOfTheirInterval) {
  const Heightmap flat = terrain_of(9, 1.0, [](double, double) { return 1.0; });
  ProbeRecorder recorder({{"g", 2.0, 2.0}}, 0.5);
  const std::vector<float> depth(flat.size(), 0.0f);
  int taken = 0;
  for (double t = 0; t < 2.01; t += 0.3)  // steps of 0.3: samples at the first step past k · 0.5
    if (recorder.due(t)) {
      recorder.record(t, flat, depth);
      ++taken;
    }
  EXPECT_EQ(taken, 4);  // at t = 0, 0.6, 1.2 and 1.5 (1.8 is short of 2.0)
  EXPECT_EQ(recorder.csv().substr(0, 25), "t,name,surface,depth,bed\n");
  EXPECT_NE(recorder.csv().find("1.500000,g,1.000000,0.000000,1.000000"), std::string::npos)
      << recorder.csv();
}

TEST(StandingWater, ScenarioEntriesSurviveTheCheckpointsParameterText) {
  const Parameters p = with_scenario(
      "[[water.bodies]]\nx0 = 0\nx1 = 8\ny0 = 0\ny1 = 8\nlevel = 0.3\n"
      "[[water.bodies]]\nx0 = 1\nx1 = 2\ny0 = 1\ny1 = 2\nlevel = 1.5\n"
      "[[probes]]\nname = \"g1\"\nx = 4.1\ny = 3.9\n");
  const Parameters back = with_scenario(parameters_toml(p));
  EXPECT_EQ(back.entries("water.bodies"), p.entries("water.bodies"));
  EXPECT_EQ(back.entries("probes"), p.entries("probes"));
  EXPECT_EQ(parameters_toml(back), parameters_toml(p));
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// The time between the two crossings of the mean level at the western wall of a closed channel
// `cells` long, 0.51 m deep, its western half 2 cm higher at t = 0.
double seiche_crossings(const std::string& flux, int cells, double cell) {
  const double length = cells * cell;
  Heightmap channel(cells + 1, 5, cell, 0.0f);
  channel.origin_x = channel.origin_z = -0.5 * cell;  // column 0 at x = 0, the last row at y = 0
  std::ostringstream toml;
  toml << "[pipe]\nrain = 0\nevaporation = 0\nedges = \"closed\"\nmanning_n = 0\ncapacity = 0\n"
       << "flux = \"" << flux << "\"\n"
       << "[[water.bodies]]\nx0 = 0\nx1 = " << 0.5 * length - 0.5 * cell << "\ny0 = 0\ny1 = 10\n"
       << "level = 0.52\n[[water.bodies]]\nx0 = " << 0.5 * length << "\nx1 = " << length
       << "\ny0 = 0\ny1 = 10\nlevel = 0.50\n";
  PipeModel model(compute(), with_scenario(toml.str()), channel);
  double fell = -1, rose = -1;
  const double end = 2.0 * length / std::sqrt(9.81 * 0.51);
  while (model.time() < end && rose < 0) {
    model.step();
    const float wall = model.depth()[2 * static_cast<std::size_t>(cells + 1)];  // row 2, column 0
    if (fell < 0 && wall < 0.51f) fell = model.time();
    if (fell >= 0 && wall > 0.51f) rose = model.time();
  }
  return rose < 0 ? 0.0 : rose - fell;
}

TEST(StandingWater, TheLocalInertialAndGodunovFluxesCarryShallowWaterWavesAtSqrtGD) {
  // In linear shallow-water theory the level at the wall is a square wave: high until the step's
  // wave arrives (L / 2c), low until it returns (3L / 2c), c = sqrt(g d): the mean level is crossed
  // twice L / c apart. The local-inertial and godunov fluxes give it within 5 % on 0.1 m and on 1 m
  // cells; Mei's pipes (1 m² on 1 m cells) give about half of it.
  for (const char* flux : {"local-inertial", "godunov"})
    for (double cell : {0.1, 1.0}) {
      const double expected = 100 * cell / std::sqrt(9.81 * 0.51);
      EXPECT_NEAR(seiche_crossings(flux, 100, cell), expected, 0.05 * expected)
          << flux << ", cells of " << cell << " m";
    }
  const double pipes = seiche_crossings("pipes", 100, 1.0), expected = 100 / std::sqrt(9.81 * 0.51);
  EXPECT_LT(pipes, 0.6 * expected) << "Mei's pipes are not the shallow-water equations' waves";
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

TEST(StandingWater, AGodunovDamBreakFollowsRittersSolution) {
  // Ritter (1892): a dam of depth h0 released on a dry frictionless bed. Behind the front
  // h = (2 c0 − ξ/t)² / 9g, c0 = sqrt(g h0), ξ from the gate, −c0 t ≤ ξ ≤ 2 c0 t; at the gate
  // 4/9 h0 whatever the time. The godunov flux carries the advection Ritter's wave needs.
  const double h0 = 0.2, g = 9.81, c0 = std::sqrt(g * h0), gate = 5.0;
  const Heightmap channel(201, 5, 0.05, 0.0f);
  Parameters p = with_scenario(
      "[pipe]\nrain = 0\nevaporation = 0\nedges = \"closed\"\nflux = \"godunov\"\nmanning_n = 0\n"
      "capacity = 0\n[[water.bodies]]\nx0 = 0\nx1 = 4.99\ny0 = 0\ny1 = 1\nlevel = 0.2\n");
  PipeModel model(compute(), p, channel);
  model.advance(1.0);
  const double t = model.time();
  const std::vector<float> depth = model.depth();
  double worst = 0;
  for (double xi : {-0.75, -0.5, -0.25, 0.0, 0.5, 1.0}) {
    const int i = static_cast<int>(std::lround((gate + xi * c0 * t) / 0.05));
    const double x = i * 0.05 - gate, r = 2 * c0 - x / t;
    const double ritter = x < -c0 * t ? h0 : r * r / (9 * g);
    worst = std::max(worst, std::abs(depth[2 * 201 + i] - ritter));
  }
  EXPECT_LT(worst, 0.05 * h0) << "worst depth error " << worst << " m";
  // The front: water 2 c0 t downstream of the gate at most, and past 1.5 c0 t.
  int front = 0;
  for (int i = 0; i < 201; ++i)
    if (depth[2 * 201 + i] > 1e-4f) front = i;
  EXPECT_LT(front * 0.05 - gate, 2 * c0 * t + 0.1);
  EXPECT_GT(front * 0.05 - gate, 1.5 * c0 * t);
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// A flume 10 m long between terrain walls, its west end closed and its east end open: a dam of
// 0.2 m at x = 5 m released on the dry, frictionless bed. Ritter's wave is supercritical past the
// gate, so the open end changes nothing upstream of it: until the rarefaction reaches the west
// wall (3.6 s) the exact depth everywhere is Ritter's, right up to the end. Water that piled up
// at the end, as against a wall, would show there first.
struct OpenFlume {
  // Vertex i stands at x = i·cell: column 0 is the west wall, the water reaches x = 4.95 m (its
  // cell's face at 4.975 m is the gate) and the last column is the open end at x = 10.05 m.
  static constexpr double h0 = 0.2, g = 9.81, gate = 4.975, cell = 0.05;
  static constexpr int nx = 202, ny = 5, row = 2;
  std::unique_ptr<PipeModel> model;

  OpenFlume(const std::string& flux, double manning_n) {
    Heightmap t(nx, ny, cell);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) t.at(i, j) = (i == 0 || j == 0 || j == ny - 1) ? 1.0f : 0.0f;
    t.origin_x = t.origin_z = -0.5 * cell;
    const Parameters p =
        with_scenario("[pipe]\nrain = 0\nevaporation = 0\nedges = \"outflow\"\nflux = \"" + flux +
                      "\"\nmanning_n = " + std::to_string(manning_n) +
                      "\ncapacity = 0\n[[water.bodies]]\nx0 = 0\nx1 = 4.96\n"
                      "y0 = -1\ny1 = 1\nlevel = 0.2\n");
    model = std::make_unique<PipeModel>(compute(), p, t);
  }
  double depth_at(double x) const {
    return model->depth()[row * nx + static_cast<int>(std::lround(x / cell))];
  }
  // The mean depth of the middle row between x0 and x1.
  double mean_depth(double x0, double x1) const {
    const std::vector<float> d = model->depth();
    double sum = 0;
    int cells = 0;
    for (int i = static_cast<int>(std::lround(x0 / cell)); i <= std::lround(x1 / cell);
         ++i, ++cells)
      sum += d[row * nx + i];
    return sum / cells;
  }
  static double ritter(double x, double t) {
    const double c0 = std::sqrt(g * h0), xi = x - gate, r = 2 * c0 - xi / t;
    if (xi < -c0 * t) return h0;
    return xi > 2 * c0 * t ? 0.0 : r * r / (9 * g);
  }
};

TEST(OpenEdges, AGodunovDamBreakLeavesAnOpenFlumeAsRittersWaveDoes) {
  OpenFlume f("godunov", 0.0);
  f.model->advance(3.0);
  const double t = f.model->time();
  double worst = 0, worst_x = 0;
  std::ostringstream profile;
  for (double x : {3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 9.5, 9.9, 10.05}) {
    const double err = f.depth_at(x) - OpenFlume::ritter(x, t);
    profile << " x=" << x << ": " << f.depth_at(x) << " (" << OpenFlume::ritter(x, t) << ")";
    if (std::abs(err) > std::abs(worst)) worst = err, worst_x = x;
  }
  // Against a wall the end would hold a reflected bore several times Ritter's 1.4 cm there.
  EXPECT_LT(std::abs(worst), 0.025 * OpenFlume::h0)
      << "worst " << worst << " m at x = " << worst_x << " m;" << profile.str();
}

TEST(OpenEdges, EveryFluxEmptiesTheReservoirThroughTheOpenEndOnly) {
  // With a flume's friction (n = 0.01). How each flux carries the wave differs (docs/models.md);
  // what none may do is hold the water back at the end, lose it, or let it out elsewhere.
  for (const char* flux : {"godunov", "local-inertial", "pipes"}) {
    OpenFlume f(flux, 0.01);
    const double v0 = f.model->water_budget()->stored;
    f.model->advance(20.0);
    const double level = f.mean_depth(0.05, 2.0);
    const WaterBudget b = *f.model->water_budget();
    std::printf("%s after %.0f s: stored %.4f of %.4f m3, out east %.4f, level upstream %.4f m\n",
                flux, f.model->time(), b.stored, v0, b.edges[1], level);
    EXPECT_NEAR(b.stored + b.edges[1], v0, 1e-4 * v0) << flux << ": the water balance";
    EXPECT_EQ(b.edges[0] + b.edges[2] + b.edges[3], 0.0) << flux << ": water left through a wall";
    EXPECT_LT(b.stored, 0.5 * v0) << flux << ": the flume keeps its water";
    EXPECT_LT(level, 0.25 * OpenFlume::h0) << flux << ": the reservoir's level stays up";
  }
}

}  // namespace
}  // namespace runnel
