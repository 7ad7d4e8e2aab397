// SPDX-License-Identifier: MIT
// Terrain collision: droplets slide down the steepest descent and never end below the surface,
// however fast they move (up to 50 m/s) and at the largest time step; same on a rough terrain.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runnel/compute/kernel.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/surface.hpp"
#include "runnel/terrain/terrain_normals.hpp"
#include "runnel/validation/tank.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

SphSettings droplet_settings(double cfl) {
  Parameters p = default_parameters();
  p.set("sph.cfl", cfl);
  p.set("sph.dt_max", 1.0);
  p.set("sph.density_max", 100.0);  // droplets slam into the ground at up to Mach 1 here
  p.set("sph.density_min", 0.01);
  return SphSettings::from(p, 0.5, 5.0);  // dx = 0.5 m, c0 = 50 m/s
}

// Möller–Trumbore in double over every triangle: the earliest downward crossing, or −1.
double brute_force_hit(const Heightmap& t, const double o[3], const double d[3]) {
  double best = -1;
  auto vertex = [&](int i, int j, double v[3]) {
    v[0] = i * t.cell;
    v[1] = t.at(i, j);
    v[2] = j * t.cell;
  };
  auto test = [&](const double a[3], const double b[3], const double c[3]) {
    double e1[3], e2[3], p[3], s[3], q[3];
    for (int k = 0; k < 3; ++k) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], s[k] = o[k] - a[k];
    p[0] = d[1] * e2[2] - d[2] * e2[1], p[1] = d[2] * e2[0] - d[0] * e2[2],
    p[2] = d[0] * e2[1] - d[1] * e2[0];
    const double det = e1[0] * p[0] + e1[1] * p[1] + e1[2] * p[2];
    if (!(det < 0)) return;
    const double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
    if (u < 0 || u > 1) return;
    q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2],
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    const double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    if (v < 0 || u + v > 1) return;
    const double tt = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    if (tt >= 0 && tt <= 1 && (best < 0 || tt < best)) best = tt;
  };
  for (int j = 0; j + 1 < t.ny; ++j) {
    for (int i = 0; i + 1 < t.nx; ++i) {
      double a[3], b[3], c[3], e[3];
      vertex(i, j, a), vertex(i + 1, j, b), vertex(i + 1, j + 1, c), vertex(i, j + 1, e);
      test(a, b, c);
      test(a, c, e);
    }
  }
  return best;
}

TEST(Collision, SegmentWalkFindsTheEarliestHitOfABruteForceSearch) {
  // Segments up to 50 m long (50 m/s for a whole second) across a rough terrain: the tile walk
  // must find the same first crossing as testing every triangle, of the terrain itself and of the
  // contact surface a particle's radius above it (whose vertex heights the terrain keeps for the
  // solver's contact radius).
  const Heightmap rough = generate_terrain("diamond-square", 49, 41, 0.5, 9, {{"relief", 0.4}});
  SphSolver solver(compute(), droplet_settings(0.25), rough, 40.0);
  Kernel probe(compute(),
               compute().program(
                   {"cl/common.cl", "cl/terrain_sample.cl", "cl/collide.cl", "cl/collide_probe.cl"},
                   droplet_settings(0.25).build_options()),
               "collide_probe");
  ASSERT_EQ(solver.settings().contact_radius, 0.25);
  for (double radius : {0.0, 0.25}) {
    const Heightmap surface = contact_surface(rough, radius);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-2.0f, 26.0f), dir(-1.0f, 1.0f), len(0.1f, 50.0f);
    const int n = 2000;
    std::vector<float> segments(6 * n);
    for (int k = 0; k < n; ++k) {
      const float x = pos(rng), z = pos(rng),
                  y = static_cast<float>(surface_height(surface, x, z)) +
                      3.0f * std::fabs(dir(rng));
      float d[3] = {dir(rng), -std::fabs(dir(rng)), dir(rng)};
      const float l = len(rng) / std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const float seg[6] = {x, y, z, d[0] * l, d[1] * l, d[2] * l};
      std::copy(seg, seg + 6, segments.begin() + 6 * k);
    }
    auto& ctx = compute().context();
    cl::Buffer seg_buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, segments.size() * 4,
                          segments.data());
    cl::Buffer result(ctx, CL_MEM_WRITE_ONLY, 4 * n * 4);
    DeviceTerrain& terrain = solver.terrain();
    probe.set("surface", radius > 0 ? terrain.contact() : terrain.height());
    terrain.bind_mesh(probe);
    probe.set("segments", seg_buffer).set("n", static_cast<cl_uint>(n));
    probe.set("result", result).launch(n);
    std::vector<float> r(4 * n);
    compute().queue().enqueueReadBuffer(result, CL_TRUE, 0, r.size() * 4, r.data());
    int hits = 0;
    for (int k = 0; k < n; ++k) {
      const double o[3] = {segments[6 * k], segments[6 * k + 1], segments[6 * k + 2]};
      const double d[3] = {segments[6 * k + 3], segments[6 * k + 4], segments[6 * k + 5]};
      const double expected = brute_force_hit(surface, o, d);
      const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (expected < 0) {
        EXPECT_LT(r[4 * k], 0.0f) << "segment " << k << " hit nothing in the brute-force search";
      } else {
        ++hits;
        ASSERT_GE(r[4 * k], 0.0f) << "segment " << k
                                  << " tunnelled (brute force hits at t = " << expected
                                  << ", radius " << radius << ")";
        ASSERT_NEAR(r[4 * k] * length, expected * length, 2e-3)
            << "segment " << k << ", radius " << radius;  // metres along the segment
        ASSERT_GT(r[4 * k + 2], 0.0f);                    // the normal points up
      }
    }
    EXPECT_GT(hits, n / 2) << "radius " << radius;
  }
}

// Lowest clearance above the contact surface over all particles (m): no particle may end a step
// inside the terrain, nor closer to it than its radius.
double min_clearance(SphSolver& solver, const Heightmap& terrain) {
  const Heightmap surface = contact_surface(terrain, solver.settings().contact_radius);
  const HostParticles p = solver.particles().download();
  double lowest = 1e30;
  for (std::size_t i = 0; i < p.size(); ++i) {
    lowest = std::min(lowest, p.f[kY][i] - surface_height(surface, p.f[kX][i], p.f[kZ][i]));
  }
  return lowest;
}

TEST(Collision, DropletSlidesDownTheSteepestDescent) {
  // A plane rising to the south-east (azimuth 30°): steepest descent points to azimuth 210°.
  const Heightmap plane =
      generate_terrain("plane", 81, 81, 0.5, 1, {{"slope", 20.0}, {"azimuth", 30.0}});
  SphSolver solver(compute(), droplet_settings(0.25), plane, 40.0);
  HostParticles p;
  const double x0 = 30, z0 = 30;
  p.push(x0, surface_height(plane, x0, z0) + 0.5, z0, 0, 0, 0, 1000, 1e30f);
  solver.add(p);
  for (int k = 0; k < 400; ++k) {
    solver.step();
    ASSERT_GE(min_clearance(solver, plane), -1e-4) << "step " << k;
  }
  const HostParticles q = solver.particles().download();
  ASSERT_EQ(q.size(), 1u);
  const double dx = q.f[kX][0] - x0, dz = q.f[kZ][0] - z0;
  ASSERT_GT(std::hypot(dx, dz), 1.0) << "the droplet did not slide";
  const double expected = (210.0) * M_PI / 180.0;
  EXPECT_NEAR(dx / std::hypot(dx, dz), std::cos(expected), 0.02);
  EXPECT_NEAR(dz / std::hypot(dx, dz), std::sin(expected), 0.02);
}

TEST(Collision, FastDropletsNeverTunnelAtTheLargestTimeStep) {
  // Rough terrain, the largest CFL factor, droplets thrown at up to 50 m/s in random directions.
  const Heightmap rough = generate_terrain("diamond-square", 65, 65, 0.5, 3, {{"relief", 0.3}});
  SphSolver solver(compute(), droplet_settings(0.5), rough, 40.0);
  const Heightmap surface = contact_surface(rough, solver.settings().contact_radius);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> pos(2.0f, 30.0f), dir(-1.0f, 1.0f), speed(5.0f, 50.0f);
  HostParticles p;
  for (int k = 0; k < 300; ++k) {
    const float x = pos(rng), z = pos(rng);
    float vx = dir(rng), vy = -std::fabs(dir(rng)) - 0.2f, vz = dir(rng);
    const float s = speed(rng) / std::sqrt(vx * vx + vy * vy + vz * vz);
    p.push(x,
           static_cast<float>(surface_height(surface, x, z)) + 0.05f + 2.0f * std::fabs(dir(rng)),
           z, vx * s, vy * s, vz * s, 1000, 1e30f);
  }
  solver.add(p);
  for (int k = 0; k < 300; ++k) {
    solver.step();
    ASSERT_GE(min_clearance(solver, rough), -1e-4) << "step " << k;
  }
  const SphCounters c = solver.counters();
  EXPECT_GT(c.collisions, 250) << "every droplet reaches the terrain: nothing holds a drop up";
  EXPECT_EQ(c.surface_projections, 0) << "the contact leaves none below the surface";
}

// Speed of a lone frictionless drop that starts at the bottom of a V-shaped valley (faces rising
// 1 : 1 on both sides) moving at 2 m/s straight into one face, after `steps` steps.
double speed_in_a_valley_after(bool face_normal, int steps) {
  Heightmap valley(33, 33, 0.25, 0.0f);
  for (int j = 0; j < 33; ++j)
    for (int i = 0; i < 33; ++i) valley.at(i, j) = static_cast<float>(std::fabs(0.25 * i - 4.0));
  Parameters p = default_parameters();
  p.set("sph.manning_n", 0.0);
  p.set("sph.contact_face_normal", face_normal);
  SphSolver solver(compute(), SphSettings::from(p, 0.5, 5.0), valley, 10.0);
  const Heightmap surface = contact_surface(valley, solver.settings().contact_radius);
  HostParticles drop;
  drop.push(4.0f, static_cast<float>(surface_height(surface, 4.0, 4.0)), 4.0f, 2.0f, 0, 0, 1000,
            1e30f);
  solver.add(drop);
  for (int k = 0; k < steps; ++k) solver.step();
  const HostParticles q = solver.particles().download();
  return std::hypot(q.f[kVx][0], q.f[kVy][0], q.f[kVz][0]);
}

TEST(Collision, AtABendTheVelocityIntoTheHitFaceIsTakenAway) {
  // The valley's bottom vertex has a vertical interpolated normal, the faces beside it lean 45°.
  // Against the faces' own normals the drop climbs a face, falls back and loses the normal part
  // of each impact (restitution 0): it comes to rest within a few bounces. Against the
  // interpolated normal alone it keeps its 2 m/s into the face while the contact stops it there
  // every step, a speed with no motion (the default, docs/sph.md, "The contact at bends").
  EXPECT_LT(speed_in_a_valley_after(true, 200), 0.2);
  EXPECT_GT(speed_in_a_valley_after(false, 200), 1.0) << "the default keeps the phantom speed";
}

TEST(Collision, AParticleLeavingThroughAnOpenEdgeIsNoProjection) {
  // A droplet thrown down and out over the map's edge: the drift books it as outflow, its last
  // position beyond the edge and below the height there. The projection that follows a terrain
  // change must leave it alone: it is gone at the next sort, and no projection happened.
  const Heightmap flat = flat_floor(8, 8, 1.0);
  SphSolver solver(compute(), droplet_settings(0.5), flat, 10.0);
  const Heightmap surface = contact_surface(flat, solver.settings().contact_radius);
  const float edge = static_cast<float>((flat.nx - 1) * flat.cell);
  HostParticles p;
  p.push(edge - 0.01f, static_cast<float>(surface_height(surface, edge, 4.0)) + 0.05f, 4.0f, 400.0f,
         -400.0f, 0, 1000, 1e30f);
  solver.add(p);
  solver.drift();
  const HostParticles after = solver.particles().download();
  ASSERT_EQ(solver.counters().outflow_particles, 1);
  ASSERT_LT(after.f[kY][0], surface_height(surface, edge, 4.0) - 2 * solver.settings().surface_eps)
      << "the case needs the droplet to end below the edge's height";
  solver.project_to_surface();
  EXPECT_EQ(solver.counters().surface_projections, 0);
}

}  // namespace
}  // namespace runnel
