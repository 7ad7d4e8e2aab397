// SPDX-License-Identifier: MIT
// The integration kernels against their plain C++ double-precision oracles: kick (v += a·dt/2)
// and drift (cl/integrate.cl: flight, the contact surface's first crossing with the timed rebound,
// the end-of-step projection, Manning's bed friction) for random particles over a tilted plane.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "runnel/compute/kernel.hpp"
#include "runnel/compute/launch.hpp"
#include "runnel/core/text.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/sph/drift_reference.hpp"
#include "runnel/sph/particle_store.hpp"
#include "runnel/sph/sph_solver.hpp"
#include "runnel/terrain/device_terrain.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using drift_reference::Vec;
using test::compute;

struct Case {
  SphSettings settings;
  drift_reference::Plane plane{2.0, 0.3, -0.15, 12.0, 10.0};
  Heightmap terrain;
  std::vector<drift_reference::Particle> particles;
};

Case random_case(double restitution, std::uint32_t seed) {
  Case c;
  Parameters p = default_parameters();
  p.set("sph.restitution", restitution);
  p.set("sph.manning_n", 0.05);
  c.settings = SphSettings::from(p, 0.25, 5.0);
  const double cell = 0.5;
  c.terrain = Heightmap(25, 21, cell);
  for (int j = 0; j < c.terrain.ny; ++j)
    for (int i = 0; i < c.terrain.nx; ++i)
      c.terrain.at(i, j) =
          static_cast<float>(c.plane.y0 + c.plane.slope_x * i * cell + c.plane.slope_z * j * cell);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), sym(-1.0, 1.0);
  const double lift = c.settings.contact_radius * std::sqrt(1 + 0.3 * 0.3 + 0.15 * 0.15);
  for (int k = 0; k < 2000; ++k) {
    drift_reference::Particle q;
    const double x = 1 + 10 * u(rng), z = 1 + 8 * u(rng);
    const double surface = c.plane.y0 + c.plane.slope_x * x + c.plane.slope_z * z + lift;
    // A third resting on the contact surface, the rest up to 0.6 m above it.
    const double gap = k % 3 == 0 ? 0.5 * c.settings.surface_eps * u(rng) : 0.6 * u(rng);
    q.x = {x, surface + gap, z};
    q.v = {3 * sym(rng), -4 * u(rng) + 1, 3 * sym(rng)};
    q.a = {sym(rng), -9.81 + 2 * sym(rng), sym(rng)};
    q.depth = 0.02 + 0.3 * u(rng);
    c.particles.push_back(q);
  }
  return c;
}

TEST(IntegrateOracle, DriftMatchesThePlainCppReferenceOverAPlane) {
  for (double restitution : {0.0, 0.6}) {
    Case c = random_case(restitution, 17);
    const double dt = 0.02;
    ParticleStore store(compute());
    HostParticles host;
    for (const auto& q : c.particles) {
      host.push(float(q.x[0]), float(q.x[1]), float(q.x[2]), float(q.v[0]), float(q.v[1]),
                float(q.v[2]), float(c.settings.rho0), 100.0f);
    }
    store.append(host);
    const std::size_t n = c.particles.size();
    const ParticleField per_particle[] = {kAx, kAy, kAz, kDepth};
    for (int f = 0; f < 4; ++f) {
      std::vector<float> values(n);
      for (std::size_t k = 0; k < n; ++k)
        values[k] = float(f < 3 ? c.particles[k].a[f] : c.particles[k].depth);
      compute().queue().enqueueWriteBuffer(store.buffer(per_particle[f]), CL_TRUE, 0, n * 4,
                                           values.data());
    }
    DeviceTerrain terrain(compute(), c.terrain);
    terrain.carry_contact_surface(float(c.settings.contact_radius));
    cl::Buffer counters(compute().context(), CL_MEM_READ_WRITE, 8 * sizeof(cl_long));
    compute().queue().enqueueFillBuffer(counters, cl_long{0}, 0, 8 * sizeof(cl_long));
    Kernel k(compute(), sph_program(compute(), c.settings, c.terrain.cell), "drift");
    store.bind(k, {kX, kY, kZ, kVx, kVy, kVz, kRho, kAge, kSediment, kContacts, kId, kAx, kAy, kAz,
                   kDepth});
    store.bind_new(k, {kX, kY, kZ});
    bind_continuity_inputs(store, k);
    Kernel factors(compute(), sph_program(compute(), c.settings, c.terrain.cell),
                   "bed_friction_factors");
    launch_bed_friction_factors(store, factors, k);
    terrain.bind_contact(k);
    k.set("domain_x", float(terrain.extent_x())).set("domain_z", float(terrain.extent_z()));
    k.set("dt", float(dt)).set("counters", counters).launch(round_up_work(n));
    std::vector<float> out[6];
    const ParticleField read[6] = {kX, kY, kZ, kVx, kVy, kVz};
    for (int f = 0; f < 6; ++f) {
      out[f].resize(n);
      cl::Buffer& b = f < 3 ? store.scratch(read[f]) : store.buffer(read[f]);
      compute().queue().enqueueReadBuffer(b, CL_TRUE, 0, n * 4, out[f].data());
    }
    // The continuity pass's inputs, written by the drift: midpoints, drift velocities, volumes.
    std::vector<float> spare[7];
    for (int k = 0; k < 7; ++k) {
      spare[k].resize(n);
      compute().queue().enqueueReadBuffer(store.spare(k), CL_TRUE, 0, n * 4, spare[k].data());
    }
    double worst_mid = 0, worst_drift_v = 0, worst_volume = 0;
    for (std::size_t q = 0; q < n; ++q) {
      for (int a = 0; a < 3; ++a) {
        const double from = float(c.particles[q].x[a]), to = out[a][q];
        worst_mid = std::max(worst_mid, std::fabs(spare[a][q] - 0.5 * (from + to)));
        worst_drift_v = std::max(worst_drift_v, std::fabs(spare[3 + a][q] - (to - from) / dt));
      }
      worst_volume = std::max(worst_volume,
                              std::fabs(spare[6][q] / (c.settings.mass() / c.settings.rho0) - 1));
    }
    EXPECT_LT(worst_mid, 2e-5) << "m";
    EXPECT_LT(worst_drift_v, 1e-4) << "m/s";
    EXPECT_LT(worst_volume, 1e-6);
    c.plane.lx = terrain.extent_x();
    c.plane.lz = terrain.extent_z();
    int touching = 0, agree = 0;
    double worst_x = 0, worst_v = 0;
    for (std::size_t q = 0; q < n; ++q) {
      const auto r = drift_reference::drift(c.particles[q], c.plane, c.settings, dt);
      touching += r.touching;
      double dx = 0, dv = 0;
      for (int a = 0; a < 3; ++a) {
        dx = std::max(dx, std::fabs(out[a][q] - r.x[a]));
        dv = std::max(dv, std::fabs(out[3 + a][q] - r.v[a]));
      }
      // Float against double: positions of metres to about 1e-5 m, velocities of m/s to 1e-4.
      if (dx < 2e-5 && dv < 2e-4) ++agree;
      worst_x = std::max(worst_x, dx);
      worst_v = std::max(worst_v, dv);
    }
    EXPECT_GT(touching, int(n) / 4) << "the case exercises the contact";
    EXPECT_LT(touching, int(n)) << "and free flight";
    // A particle whose float and double paths part at a threshold (the ε band, the held-on-surface
    // test) may differ; they are rare.
    EXPECT_GE(agree, int(0.995 * n)) << "worst |Δx| " << worst_x << " m, |Δv| " << worst_v
                                     << " m/s, restitution " << restitution;
  }
}

// The drift's bed friction factors, g n² / D^(4/3), taken LANES particles a work-item with the
// vector cube root: on a CPU (PoCL) bit for bit what the drift computed for one particle with the
// scalar root (a kernel built here from that expression, with the SPH program's division), and
// within 2 ulp of the double-precision value (a GPU, whose bits are its own: within its division's
// and root's few ulp), D floored at 1 µm, for depths across eleven decades, exact cubes and a
// partial last work-item; nothing written past the particles.
TEST(IntegrateOracle, BedFrictionFactorsAreTheScalarRootsBitsInEveryLane) {
  Parameters p = default_parameters();
  p.set("sph.manning_n", 0.035);
  const SphSettings s = SphSettings::from(p, 0.25, 5.0);
  std::vector<float> depth = {0.0f, -1.0f, 1e-7f, 1e-6f, 0.001f, 0.008f, 0.125f, 1.0f, 8.0f, 27.0f};
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> decades(-6.0, 5.0);
  while (depth.size() < 8 * 300 + 5) depth.push_back(float(std::pow(10.0, decades(rng))));
  const std::size_t n = depth.size();
  HostParticles host;
  for (std::size_t k = 0; k < n; ++k) host.push(0, 0, 0, 0, 0, 0, 1000, 1);
  ParticleStore store(compute(), n + 64);
  store.append(host);
  compute().queue().enqueueWriteBuffer(store.buffer(kDepth), CL_TRUE, 0, n * 4, depth.data());
  const float sentinel = -7.0f;
  compute().queue().enqueueFillBuffer(store.scratch(kRho), sentinel, 0, (n + 64) * 4);
  cl::Program& program = sph_program(compute(), s, 1.0);
  Kernel factors(compute(), program, "bed_friction_factors"), drift(compute(), program, "drift");
  launch_bed_friction_factors(store, factors, drift);
  std::vector<float> got(n + 64);
  compute().queue().enqueueReadBuffer(store.scratch(kRho), CL_TRUE, 0, got.size() * 4, got.data());

  const double g_n2 = s.gravity * s.manning_n * s.manning_n;
  cl::Program scalar =
      compute().build_source(R"(
__kernel void scalar_factors(const __global float* depth, const uint n, __global float* out) {
  const uint i = get_global_id(0);
  if (i >= n) return;
  const float d = fmax(depth[i], 1e-6f);
  out[i] = G_N2 / (d * cbrt(d));
})",
                             float_define("G_N2", g_n2), ComputeContext::Division::device);
  Kernel one(compute(), scalar, "scalar_factors");
  cl::Buffer out(compute().context(), CL_MEM_READ_WRITE, n * 4);
  one.set("depth", store.buffer(kDepth))
      .set("n", cl_uint(n))
      .set("out", out)
      .launch(round_up_work(n));
  std::vector<float> expected(n);
  compute().queue().enqueueReadBuffer(out, CL_TRUE, 0, n * 4, expected.data());
  const bool cpu = compute().info().type == "CPU";
  for (std::size_t k = 0; k < n; ++k) {
    if (cpu) {
      ASSERT_EQ(std::memcmp(&got[k], &expected[k], 4), 0)
          << "depth " << depth[k] << ": " << got[k] << " against the scalar root's " << expected[k];
    }
    const double d = std::max(double(depth[k]), double(1e-6f));
    const double exact = g_n2 / (d * std::cbrt(d));
    ASSERT_NEAR(got[k], exact, (cpu ? 2.5e-7 : 1e-6) * exact) << "depth " << depth[k];
  }
  for (std::size_t k = n; k < got.size(); ++k)
    ASSERT_EQ(got[k], sentinel) << "written past the particles";
}

// Each particle is kicked once and measured, whether the rows take contiguous runs (a CPU's cut) or
// every blocks-th particle (a GPU's).
TEST(IntegrateOracle, ClosingKickAddsHalfTheAccelerationStepBeforeTheStats) {
  const SphSettings s = SphSettings::from(default_parameters(), 0.25, 5.0);
  HostParticles host;
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  const std::size_t n = 257;
  for (std::size_t k = 0; k < n; ++k)
    host.push(u(rng), u(rng), u(rng), u(rng), u(rng), u(rng), 1000, 1);
  std::vector<float> a[3];
  for (auto& field : a) {
    field.resize(n);
    for (float& v : field) v = 20.0f * u(rng);
  }
  const cl_uint blocks = 4, chunk = (n + blocks - 1) / blocks;
  for (const bool interleaved : {false, true}) {
    SCOPED_TRACE(interleaved ? "interleaved rows" : "contiguous rows");
    ParticleStore store(compute());
    store.append(host);
    const ParticleField acc[3] = {kAx, kAy, kAz};
    for (int f = 0; f < 3; ++f)
      compute().queue().enqueueWriteBuffer(store.buffer(acc[f]), CL_TRUE, 0, n * 4, a[f].data());
    // The closing kick lives in the step statistics kernel, which then measures the kicked state.
    Kernel k(compute(), sph_program(compute(), s, 1.0), "step_stats");
    store.bind(k, {kVx, kVy, kVz, kAx, kAy, kAz, kRho, kDrho});
    const double half_dt = 0.0037;
    cl::Buffer stats(compute().context(), CL_MEM_READ_WRITE, 64 * 6 * sizeof(float));
    k.set("chunk", chunk).set("chunk_stride", interleaved ? 1 : chunk);
    k.set("stride", interleaved ? blocks : 1).set("blocks", blocks);
    k.set("kick", cl_uint{1}).set("half_dt", float(half_dt)).set("stats", stats).launch(64);
    std::vector<float> rows(blocks * 6);
    compute().queue().enqueueReadBuffer(stats, CL_TRUE, 0, rows.size() * 4, rows.data());
    const HostParticles after = store.download();
    const ParticleField vel[3] = {kVx, kVy, kVz};
    double v2max = 0;
    for (std::size_t q = 0; q < n; ++q) {
      double v2 = 0;
      for (int f = 0; f < 3; ++f) {
        const double expected = double(host.f[vel[f]][q]) + double(a[f][q]) * half_dt;
        ASSERT_NEAR(after.f[vel[f]][q], expected, 1e-6 * (1 + std::fabs(expected))) << q;
        v2 += expected * expected;
      }
      v2max = std::max(v2max, v2);
    }
    float measured = 0;
    for (cl_uint b = 0; b < blocks; ++b) measured = std::max(measured, rows[6 * b]);
    EXPECT_NEAR(measured, v2max, 1e-5 * v2max) << "max |v|² of the kicked velocities";
    // Without the kick the kernel only measures.
    k.set("kick", cl_uint{0}).launch(64);
    const HostParticles again = store.download();
    EXPECT_EQ(again.f[kVx], after.f[kVx]);
  }
}

}  // namespace
}  // namespace runnel
