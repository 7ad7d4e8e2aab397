// SPDX-License-Identifier: MIT
// erode_exchange against its plain C++ oracle (erosion_reference): detachment below the transport
// capacity, deposition above it, evaporation with a partial deposit, the acidity and the bed-load
// models, on a
// rough terrain with the footprint spreading every amount.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/erosion.hpp"
#include "runnel/sph/erosion_reference.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/surface.hpp"
#include "runnel/terrain/terrain_normals.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

TEST(ErosionOracle, ExchangeMatchesThePlainCppReference) {
  const Heightmap rough = generate_terrain("diamond-square", 33, 29, 1.0, 7, {{"relief", 0.3}});
  for (const char* model : {"stream-power", "acidity", "bedload"}) {
    Parameters p = default_parameters();
    p.set("erosion.model", std::string(model));
    p.set("erosion.deposit_fraction", 0.75);
    p.set("erosion.erodibility", 0.05);  // about a hundred quanta per detaching particle and step
    p.set("erosion.capacity_contacts", std::int64_t{5});
    const SphSettings sph = SphSettings::from(p, 0.5, 5.0);
    SphSolver solver(compute(), sph, rough, 40.0);
    const ErosionSettings settings = ErosionSettings::from(p, sph, rough.cell);
    const double Q = solver.terrain().volume_quantum();
    const std::vector<float> normals = terrain_normals_reference(rough);
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(0.0, 1.0), sym(-1.0, 1.0);
    HostParticles host;
    std::vector<float> depth;
    for (int k = 0; k < 3000; ++k) {
      const double x = 1 + 30 * u(rng), z = 1 + 26 * u(rng);
      const SurfacePointReference s = surface_point(rough, normals, x, z);
      const double D = 0.05 + 0.3 * u(rng);
      // Most within the water on the bed, a tenth falling above it.
      const double gap = k % 10 == 0 ? D + 0.2 : D * u(rng);
      const double lift = (sph.contact_radius + gap) / s.normal[1];
      host.push(float(x), float(s.height + lift), float(z), float(3 * sym(rng)), float(sym(rng)),
                float(3 * sym(rng)), float(sph.rho0), 10.0f);
      host.f[kAge].back() = k % 7 == 0 ? 11.0f : 1.0f;  // a seventh at the end of their life
      // Loads from empty to twice the transport capacity there: half detach, half deposit.
      const double sin_slope = std::sqrt(1 - s.normal[1] * s.normal[1]);
      const double c_t =
          std::min(settings.transport * sph.rho0 * sph.gravity / settings.bed_density * sin_slope,
                   settings.max_concentration);
      host.sediment.back() =
          static_cast<std::int32_t>(2 * u(rng) * c_t * std::pow(sph.spacing, 3) / Q);
      host.contacts.back() = static_cast<std::uint32_t>(k % 8);
      depth.push_back(float(D));
      host.id.back() = static_cast<std::uint32_t>(k);  // as the store numbers them
    }
    solver.add(host);
    const std::size_t n = host.size();
    compute().queue().enqueueWriteBuffer(solver.particles().buffer(kDepth), CL_TRUE, 0, n * 4,
                                         depth.data());
    const double dt = 0.02;
    const std::uint64_t seed = 5;
    Erosion erosion(compute(), settings, solver, seed);
    erosion.exchange(solver, dt);
    const HostParticles after = solver.particles().download();
    std::vector<std::int64_t> delta(rough.size());
    compute().queue().enqueueReadBuffer(solver.terrain().delta(), CL_TRUE, 0, delta.size() * 8,
                                        delta.data());
    const auto ref =
        erosion_reference::exchange(host, depth, rough, sph, settings, Q, dt, seed, solver.steps());
    int agree = 0, exchanged = 0;
    for (std::size_t k = 0; k < n; ++k) {
      agree += std::abs(after.sediment[k] - ref.sediment[k]) <= 1 && after.id[k] == ref.id[k];
      exchanged += ref.sediment[k] != host.sediment[k];
    }
    EXPECT_GT(exchanged, int(n) / 2) << model;
    // Stochastic rounding floor(V/Q + u) in float and double parts now and then.
    EXPECT_GE(agree, int(0.995 * n)) << model;
    double differ = 0, moved = 0;
    for (std::size_t k = 0; k < delta.size(); ++k) {
      differ += std::abs(delta[k] - ref.delta[k]);
      moved += std::abs(ref.delta[k]);
    }
    EXPECT_GT(moved, 1e4) << model;
    EXPECT_LT(differ, 0.01 * moved) << model << ": quanta placed elsewhere or not at all";
    const SphCounters c = solver.counters();
    EXPECT_EQ(c.evaporated_particles, ref.evaporated) << model;
    EXPECT_NEAR(double(c.lost_sediment), double(ref.lost), 0.01 * ref.evaporated) << model;
  }
}

// The transport capacity counts the bed's slope along the flow (docs/erosion.md): on a 20° plane,
// water running straight down detaches at the slope's full capacity, water running across the slope
// or climbing it has none, so it detaches nothing and drops what it carries. (Counting the plane's
// steepness whatever the direction, water climbing out of a hollow went on digging it.)
TEST(ErosionLaw, WaterThatClimbsOrCrossesTheSlopeDropsItsLoadAndDetachesNothing) {
  const double slope = 20.0, a = slope * M_PI / 180, speed = 2.0;
  const Heightmap plane =
      generate_terrain("plane", 41, 41, 1.0, 1, {{"slope", slope}});  // rises to +x
  Parameters p = default_parameters();
  p.set("erosion.erodibility", 0.05);
  const SphSettings sph = SphSettings::from(p, 0.5, 5.0);
  SphSolver solver(compute(), sph, plane, 40.0);
  const ErosionSettings settings = ErosionSettings::from(p, sph, plane.cell);
  const double Q = solver.terrain().volume_quantum(), volume = std::pow(sph.spacing, 3);
  const double capacity_down =
      std::min(settings.transport * sph.rho0 * sph.gravity / settings.bed_density * std::sin(a),
               settings.max_concentration);
  struct Case {
    const char* name;
    double ux, uz;  // direction of the velocity, along the bed
  };
  // Down the plane is −x; across it ±z; up it +x.
  const Case cases[] = {{"down", -1, 0}, {"across", 0, 1}, {"up", 1, 0}};
  const int per_case = 200;
  HostParticles host;
  std::vector<float> depth;
  for (const Case& c : cases) {
    for (int k = 0; k < 2 * per_case; ++k) {
      const double x = 10 + (k % 20), z = 10 + (k / 20) % 20;
      const double D = 0.3, lift = (sph.contact_radius + 0.5 * D) / std::cos(a);
      // Along the bed: the x direction climbs at the plane's angle.
      const double vx = speed * c.ux * std::cos(a), vy = speed * c.ux * std::sin(a),
                   vz = speed * c.uz;
      host.push(float(x), float(surface_height(plane, x, z) + lift), float(z), float(vx), float(vy),
                float(vz), float(sph.rho0), 10.0f);
      host.f[kAge].back() = 1.0f;
      // Half empty, half carrying half the capacity the plane has straight down.
      host.sediment.back() =
          k % 2 ? static_cast<std::int32_t>(0.5 * capacity_down * volume / Q) : 0;
      host.id.back() = static_cast<std::uint32_t>(host.size() - 1);
      depth.push_back(float(D));
    }
  }
  solver.add(host);
  compute().queue().enqueueWriteBuffer(solver.particles().buffer(kDepth), CL_TRUE, 0,
                                       depth.size() * 4, depth.data());
  Erosion erosion(compute(), settings, solver, 3);
  erosion.exchange(solver, 0.02);
  const HostParticles after = solver.particles().download();
  for (std::size_t c = 0; c < std::size(cases); ++c) {
    std::int64_t taken_by_empty = 0, change_of_loaded = 0;
    for (int k = 0; k < 2 * per_case; ++k) {
      const std::size_t i = c * 2 * per_case + k;
      (k % 2 ? change_of_loaded : taken_by_empty) += after.sediment[i] - host.sediment[i];
    }
    const std::string name = cases[c].name;
    if (name == "down") {
      EXPECT_GT(taken_by_empty, 0) << "water running down the plane detaches";
      EXPECT_GT(change_of_loaded, 0) << "below the capacity it keeps detaching";
    } else {
      EXPECT_EQ(taken_by_empty, 0) << name << ": no slope along the flow, no detachment";
      EXPECT_LT(change_of_loaded, 0) << name << ": the load settles";
    }
  }
}

}  // namespace
}  // namespace runnel
