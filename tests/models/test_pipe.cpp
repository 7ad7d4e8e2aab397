// SPDX-License-Identifier: MIT
// The virtual-pipe model (Mei 2007) in OpenCL: finite and non-negative for 10,000 steps on a rough
// terrain under heavy rain, conserving terrain + sediment + outflow exactly, deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "runnel/compute/launch.hpp"
#include "runnel/core/error.hpp"
#include "runnel/models/fields.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/pipe_model.hpp"
#include "runnel/models/pipe_reference.hpp"
#include "runnel/terrain/generators.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

// Mei's pipes (pipe.flux = "pipes"), whose kernels and oracle these tests follow.
Parameters mei_parameters() {
  Parameters p = default_parameters();
  p.set("pipe.flux", std::string("pipes"));
  return p;
}

TEST(PipeModel, StaysFiniteAndConservesUnderHeavyRain) {
  const Heightmap rough =
      generate_terrain("diamond-square", 49, 49, 1.0, 4, {{"relief", 0.3}, {"roughness", 0.5}});
  Parameters p = mei_parameters();
  p.set("pipe.rain", 0.2);  // heavy: 20 cm of water a second
  PipeModel model(compute(), p, rough);
  DeviceTerrain& terrain = model.state().terrain();
  const auto before = terrain.download_fixed();
  for (int k = 0; k < 10000; ++k) model.step();
  const auto depth = model.depth();
  for (float d : depth) {
    ASSERT_TRUE(std::isfinite(d));
    ASSERT_GE(d, 0.0f);
  }
  EXPECT_GT(*std::max_element(depth.begin(), depth.end()), 0.01f) << "water collects somewhere";
  const auto after = terrain.download_fixed();
  EXPECT_NE(before, after) << "the water erodes";
  const long long b0 = std::accumulate(before.begin(), before.end(), 0LL),
                  b1 = std::accumulate(after.begin(), after.end(), 0LL);
  EXPECT_EQ(b1 + model.suspended_quanta() + model.outflow_quanta(), b0);
  EXPECT_GT(model.time(), 0.0);
  EXPECT_LE(model.dt(), 0.05);
}

TEST(PipeModel, ErodedVolumeDoesNotMoveWithTheTimeStep) {
  // Rates per second, exact relaxation over a step, stochastic rounding instead of truncation and
  // Manning's bed friction on the pipe flow: halving the CFL factor barely moves the result.
  const Heightmap hills = generate_terrain("fbm", 65, 65, 2.0, 7, {{"relief", 0.12}});
  std::vector<double> eroded;
  for (double cfl : {0.25, 0.125}) {
    Parameters p = mei_parameters();
    p.set("pipe.cfl", cfl);
    PipeModel model(compute(), p, hills);
    while (model.time() < 20.0) model.step();
    eroded.push_back(model.mass_balance().eroded);
  }
  EXPECT_GT(eroded[0], 100.0);
  EXPECT_NEAR(eroded[1], eroded[0], 0.03 * eroded[0]);
}

TEST(PipeModel, IsDeterministic) {
  std::vector<std::vector<std::int64_t>> results;
  for (int run = 0; run < 2; ++run) {
    PipeModel model(compute(), mei_parameters(),
                    generate_terrain("fbm", 41, 41, 1.0, 2, {{"relief", 0.2}}));
    for (int k = 0; k < 300; ++k) model.step();
    results.push_back(model.state().terrain().download_fixed());
  }
  EXPECT_EQ(results[0], results[1]);
}

// A collapsing time step stops the run with an error naming the step, never carries on.
TEST(PipeModel, TimeStepCollapseStopsTheRun) {
  Parameters p = mei_parameters();
  p.set("pipe.rain", 0.5);
  p.set("pipe.dt_min", 0.045);  // absurdly large, so that the CFL step falls below it
  PipeModel model(compute(), p,
                  generate_terrain("diamond-square", 33, 33, 1.0, 4, {{"relief", 0.5}}));
  try {
    for (int k = 0; k < 2000; ++k) model.step();
    FAIL() << "the step never fell below pipe.dt_min";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("time step collapsed"), std::string::npos) << e.what();
    EXPECT_EQ(e.code(), ExitCode::kRuntime);
  }
}

// Mei's semi-Lagrangian advection does not conserve sediment: the option reports what it loses, so
// the balance still closes exactly, with a non-zero lost term.
TEST(PipeModel, SemiLagrangianReportsItsLossExactly) {
  Parameters p = mei_parameters();
  p.set("pipe.transport", std::string("semi-lagrangian"));
  p.set("pipe.rain", 0.05);
  PipeModel model(compute(), p, generate_terrain("fbm", 41, 41, 1.0, 3, {{"relief", 0.3}}));
  for (int k = 0; k < 400; ++k) model.step();
  const MassBalance m = model.mass_balance();
  EXPECT_GT(m.eroded, 0.0);
  EXPECT_NE(model.lost_quanta(), 0) << "advection by interpolation creates or destroys sediment";
  EXPECT_EQ(m.residual_quanta, 0) << "terrain + suspended + outflow + lost";
  EXPECT_DOUBLE_EQ(m.lost, model.lost_quanta() * model.state().terrain().volume_quantum());
}

// The oracle's state at the model's start (its terrain; no water, flux or sediment), and both
// stepped side by side, the oracle with the model's Δt and step index.
pipe_reference::State oracle_start(PipeModel& model) {
  const std::size_t n = model.state().vertices();
  return {model.state().terrain().download_fixed(), std::vector<std::int64_t>(n, 0),
          std::vector<double>(n, 0.0), std::vector<double>(4 * n, 0.0),
          std::vector<double>(2 * n, 0.0)};
}

void step_beside_oracle(PipeModel& model, pipe_reference::State& ref, const Parameters& p,
                        int steps) {
  const DeviceTerrain& terrain = model.state().terrain();
  const auto seed = static_cast<std::uint64_t>(p.integer("run.seed"));
  for (int k = 0; k < steps; ++k) {
    pipe_reference::step(ref, terrain.nx(), terrain.ny(), terrain.cell(), terrain.quantum(),
                         PipeSettings::from(p), model.dt(), seed, model.steps());
    model.step();
  }
}

// The outfluxes and velocities against the oracle's, within 1e-3 of the largest. Fields of several
// components come back interleaved per vertex (the device stores them one plane per component), as
// the oracle holds them.
void expect_water_fields_match(PipeModel& model, const pipe_reference::State& ref,
                               const std::string& edges) {
  for (const auto& [name, oracle] : {std::pair{kSurfaceWaterOutflux, &ref.flux},
                                     std::pair{kSurfaceWaterVelocity, &ref.velocity}}) {
    const auto values = model.state().download_float(name);
    ASSERT_EQ(values.size(), oracle->size());
    double field_worst = 0, field_scale = 0;
    for (std::size_t k = 0; k < values.size(); ++k) {
      field_worst = std::max(field_worst, std::fabs(values[k] - (*oracle)[k]));
      field_scale = std::max(field_scale, std::fabs((*oracle)[k]));
    }
    EXPECT_GT(field_scale, 0.0) << name;
    EXPECT_LT(field_worst, 1e-3 * field_scale) << edges << " " << name;
  }
}

// Five adaptive steps on a random rough terrain against the plain C++ oracle (pipe_reference),
// with outflow edges and Manning friction (the defaults) and with closed edges.
TEST(PipeModel, StepsMatchThePlainCppReference) {
  const int nx = 19, ny = 15;
  const Heightmap rough = test::rough_terrain(nx, ny, 1.0f, 12);
  for (const char* edges : {"outflow", "closed"}) {
    Parameters p = mei_parameters();
    p.set("pipe.edges", std::string(edges));
    p.set("pipe.rain", 0.2);  // deep enough water after a few steps to carry sediment
    PipeModel model(compute(), p, rough);
    DeviceTerrain& terrain = model.state().terrain();
    const std::size_t n = rough.size();
    pipe_reference::State ref = oracle_start(model);
    const auto before = ref.height;
    step_beside_oracle(model, ref, p, 5);
    const auto h = test::compare_quanta(terrain.download_fixed(), ref.height, before);
    EXPECT_GT(h.changed, static_cast<std::int64_t>(n / 2)) << edges;
    EXPECT_LE(h.worst, 2) << edges << ": stochastic rounding may tip a quantum either way";
    EXPECT_GT(h.exact_share, 0.95) << edges;
    const auto s = test::compare_quanta(model.state().download_int64(kSedimentSuspended),
                                        ref.sediment, std::vector<std::int64_t>(n, 0));
    EXPECT_LE(s.worst, 4) << edges;
    const auto depth = model.depth();
    double worst = 0;
    for (std::size_t k = 0; k < n; ++k) worst = std::max(worst, std::fabs(depth[k] - ref.depth[k]));
    EXPECT_LT(worst, 1e-5) << edges << ": m, float against double over five steps";
    expect_water_fields_match(model, ref, edges);
    EXPECT_NEAR(static_cast<double>(model.outflow_quanta()), static_cast<double>(ref.outflow),
                4.0 + 1e-3 * ref.outflow)
        << edges;
  }
}

// The Godunov flux's water over ten steps of rain on a random rough terrain, against its plain C++
// oracle, with outflow and closed edges: the reconstructed bed's slopes, the faces and the update.
// Nothing erodes (capacity 0), so the oracle steps the same bed.
TEST(PipeModel, TheGodunovWaterMatchesThePlainCppReference) {
  const int nx = 19, ny = 15;
  const Heightmap rough = test::rough_terrain(nx, ny, 1.0f, 12);
  for (const char* edges : {"outflow", "closed"}) {
    Parameters p = mei_parameters();
    p.set("pipe.edges", std::string(edges));
    p.set("pipe.flux", std::string("godunov"));
    p.set("pipe.capacity", 0.0);
    p.set("pipe.rain", 0.2);
    PipeModel model(compute(), p, rough);
    pipe_reference::State ref = oracle_start(model);
    const DeviceTerrain& terrain = model.state().terrain();
    const PipeSettings settings = PipeSettings::from(p);
    for (int k = 0; k < 10; ++k) {
      pipe_reference::godunov_water(ref, nx, ny, terrain.cell(), terrain.quantum(), settings,
                                    model.dt());
      model.step();
    }
    const auto depth = model.depth();
    double worst = 0, deepest = 0;
    for (std::size_t k = 0; k < depth.size(); ++k) {
      worst = std::max(worst, std::fabs(depth[k] - ref.depth[k]));
      deepest = std::max(deepest, ref.depth[k]);
    }
    EXPECT_GT(deepest, 0.1) << edges;
    EXPECT_LT(worst, 1e-5 * std::max(1.0, deepest)) << edges << ": m, float against double";
    expect_water_fields_match(model, ref, edges);
  }
}

// pipe_send shares at most kPipeSendable quanta of a cell's sediment (32-bit arithmetic, pipe.cl).
// A fine quantum and a large capacity put several times that in cells: the kernels still follow the
// oracle, which applies the same rule in 64 bits and double precision (a wrapped 32-bit share would
// be off by up to 2^31 quanta), and the volume stays exact.
TEST(PipeModel, FollowsTheOracleWhenACellHoldsMoreSedimentThanOneStepShares) {
  const int nx = 19, ny = 15;
  const Heightmap rough = test::rough_terrain(nx, ny, 1.0f, 5);
  Parameters p = mei_parameters();
  p.set("erosion.height_quantum", 1e-11, "test");
  p.set("pipe.rain", 0.2, "test");
  p.set("pipe.capacity", 100.0, "test");
  PipeModel model(compute(), p, rough);
  DeviceTerrain& terrain = model.state().terrain();
  const std::size_t n = rough.size();
  pipe_reference::State ref = oracle_start(model);
  const long long total = std::accumulate(ref.height.begin(), ref.height.end(), 0LL);
  step_beside_oracle(model, ref, p, 5);
  const auto sediment = model.state().download_int64(kSedimentSuspended);
  const auto fixed = terrain.download_fixed();
  EXPECT_EQ(std::accumulate(fixed.begin(), fixed.end(), 0LL) +
                std::accumulate(sediment.begin(), sediment.end(), 0LL) + model.outflow_quanta(),
            total);
  const long long most = *std::max_element(ref.sediment.begin(), ref.sediment.end());
  EXPECT_GT(most, 4 * kPipeSendable) << "the case must put more than the cap in a cell";
  long long worst = 0;
  for (std::size_t k = 0; k < n; ++k)
    worst = std::max(worst, std::llabs(sediment[k] - ref.sediment[k]));
  // float32 against double: the amounts follow the float depth and capacity (1.5e-7 of the largest
  // measured; a wrapped share is off by 8e-2).
  EXPECT_LE(static_cast<double>(worst), 1e-5 * static_cast<double>(most)) << "quanta, of " << most;
}

}  // namespace
}  // namespace runnel

namespace runnel {
namespace {

// pipe_stats against a host computation of what the time step needs: the largest depth and the
// largest counted speed (pipe_water's cfl_speed2) per block; a NaN in either reaches the host; a −0
// is not a maximum.
TEST(PipeModel, StatsKernelFindsTheMaximaAndLetsANaNThrough) {
  const int nx = 30, ny = 10, n = nx * ny, blocks = 3, chunk = 100;
  cl::Program& program = compute().program({"cl/common.cl", "cl/models/pipe.cl"},
                                           PipeSettings::from(mei_parameters()).build_options());
  Kernel stats(compute(), program, "pipe_stats");
  std::vector<float> depth(n), speed2(n);
  for (int k = 0; k < n; ++k) {
    depth[k] = 0.02f + 0.001f * static_cast<float>(k % 37);
    speed2[k] = 0.01f * static_cast<float>(k % 11);
  }
  depth[5] = -0.0f;
  depth[250] = std::nanf("");  // block 2's depth
  speed2[60] = std::nanf("");  // block 0's speed
  speed2[130] = -0.0f;
  const auto upload = [&](const std::vector<float>& v) {
    return cl::Buffer(compute().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                      v.size() * sizeof(float), const_cast<float*>(v.data()));
  };
  cl::Buffer d = upload(depth), v = upload(speed2),
             out(compute().context(), CL_MEM_READ_WRITE, 4 * blocks * sizeof(float));
  stats.set("depth", d).set("cfl_speed2", v).set("nx", nx).set("ny", ny).set("chunk", chunk);
  stats.set("stats", out).launch(blocks);
  std::vector<float> got(4 * blocks);
  compute().queue().enqueueReadBuffer(out, CL_TRUE, 0, got.size() * sizeof(float), got.data());
  EXPECT_TRUE(std::isnan(got[1])) << "block 0: the NaN speed";
  EXPECT_TRUE(std::isnan(got[8])) << "block 2: the NaN depth";
  // Block 1 (cells 100..199) on the host; its discharge and discharge-weighted Froude sums count
  // only the cells off the map's edge (the edge cells are brinks).
  float dmax = 0, v2max = 0;
  double discharge = 0, discharge_froude = 0;
  for (int k = 100; k < 200; ++k) {
    dmax = std::max(dmax, depth[k]);
    v2max = std::max(v2max, speed2[k]);
    const int i = k % nx, j = k / nx;
    if (i == 0 || i == nx - 1 || j == 0 || j == ny - 1 || !(speed2[k] > 0)) continue;
    const double speed = std::sqrt(static_cast<double>(speed2[k])), h = depth[k];
    discharge += speed * h;
    discharge_froude += speed * h * speed / std::sqrt(9.81 * h);
  }
  EXPECT_EQ(got[4], dmax);
  EXPECT_FLOAT_EQ(got[5], std::sqrt(v2max));
  EXPECT_NEAR(got[6], discharge, 1e-5 * discharge);
  EXPECT_NEAR(got[7], discharge_froude, 1e-5 * discharge_froude);
  EXPECT_FALSE(std::signbit(got[0])) << "a −0 depth is not the maximum of block 0";
  EXPECT_GT(got[0], 0.02f);
}

// pipe_water leaves the speed² the next step's CFL limit counts: only where the water left after
// evaporation is at least pipe.cfl_depth deep and the outflow did not drain the cell (the flux
// limit K acted); a NaN passes through. Checked against the rule applied on the host to the depth,
// velocity and d1 the kernel wrote.
TEST(PipeModel, WaterPassCountsTheSpeedOfDeepUndrainedCellsOnly) {
  const int nx = 8, ny = 6, n = nx * ny;
  const float cell = 2.0f, dt = 0.01f, evaporation = 0.9f;
  const PipeSettings settings = PipeSettings::from(mei_parameters());
  cl::Program& program =
      compute().program({"cl/common.cl", "cl/models/pipe.cl"}, settings.build_options());
  Kernel water(compute(), program, "pipe_water");
  std::vector<float> depth(n), flux(4 * n), height(n, 0.0f), rain(n, 1.0f);
  for (int k = 0; k < n; ++k) {
    depth[k] =
        0.005f + 0.004f * static_cast<float>(k % 9);  // some below cfl_depth after evaporation
    for (int d = 0; d < 4; ++d) flux[d * n + k] = 0.02f * static_cast<float>((k * 7 + d * 3) % 5);
  }
  // Cell 20's outflow takes all its water (the limit K acted) while cell 19 pours into it: deep
  // after the step, but its speed is its volume leaving in one step and must not count.
  depth[20] = 0.02f;
  for (int d = 0; d < 4; ++d) flux[d * n + 20] = d == 1 ? depth[20] * cell * cell / dt : 0.0f;
  flux[1 * n + 19] = 10.0f;
  flux[2 * n + 33] = std::nanf("");  // cell 33 (and the cell it flows into) carry a NaN
  const auto upload = [&](const std::vector<float>& v) {
    return cl::Buffer(compute().context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR,
                      v.size() * sizeof(float), const_cast<float*>(v.data()));
  };
  cl::Buffer d = upload(depth), f = upload(flux), h = upload(height), r = upload(rain);
  cl::Buffer velocity(compute().context(), CL_MEM_READ_WRITE, 2 * n * sizeof(float)),
      previous(compute().context(), CL_MEM_READ_WRITE, n * sizeof(float)),
      capacity(compute().context(), CL_MEM_READ_WRITE, n * sizeof(float)),
      speed2(compute().context(), CL_MEM_READ_WRITE, n * sizeof(float));
  water.set("depth", d).set("flux", f).set("velocity", velocity).set("previous_depth", previous);
  water.set("height_view", h)
      .set("capacity", capacity)
      .set("nx", nx)
      .set("ny", ny)
      .set("cell", cell);
  water.set("dt", dt)
      .set("rain_weight", r)
      .set("rain_on", 0.0f)
      .set("evaporation_factor", evaporation);
  water.set("cfl_speed2", speed2).launch(round_up_work(n));
  const auto download = [&](cl::Buffer& b, std::size_t count) {
    std::vector<float> v(count);
    compute().queue().enqueueReadBuffer(b, CL_TRUE, 0, count * sizeof(float), v.data());
    return v;
  };
  const auto left = download(d, n), v = download(velocity, 2 * n), d1 = download(previous, n),
             got = download(speed2, n);
  int counted = 0, thin = 0;
  for (int k = 0; k < n; ++k) {
    const float out = flux[k] + flux[n + k] + flux[2 * n + k] + flux[3 * n + k];
    if (std::isnan(out) || std::isnan(v[k]) || std::isnan(v[n + k])) {
      EXPECT_TRUE(std::isnan(got[k])) << "cell " << k;
      continue;
    }
    // The depth left is d2 = d1 + Δt(Σin − Σout)/l², evaporated.
    const int i = k % nx, j = k / nx;
    const float in = (i > 0 ? flux[n + k - 1] : 0.0f) + (i < nx - 1 ? flux[k + 1] : 0.0f) +
                     (j > 0 ? flux[3 * n + k - nx] : 0.0f) +
                     (j < ny - 1 ? flux[2 * n + k + nx] : 0.0f);
    if (!std::isnan(in)) {
      EXPECT_FLOAT_EQ(left[k],
                      std::max(0.0f, d1[k] + dt * (in - out) / (cell * cell)) * evaporation)
          << "cell " << k;
    }
    const bool drained = out * dt >= 0.999f * d1[k] * cell * cell;
    const bool deep = left[k] >= static_cast<float>(settings.cfl_depth);
    const float v2 = v[k] * v[k] + v[n + k] * v[n + k];
    if (deep && !drained) {
      EXPECT_FLOAT_EQ(got[k], v2) << "cell " << k;
      ++counted;
    } else {
      EXPECT_EQ(got[k], 0.0f) << "cell " << k;
      thin += deep ? 0 : 1;
    }
  }
  EXPECT_GT(counted, 5) << "the case has counted cells";
  EXPECT_GT(thin, 5) << "and thin ones";
  const float out20 = flux[20] + flux[n + 20] + flux[2 * n + 20] + flux[3 * n + 20];
  EXPECT_GE(out20 * dt, 0.999f * d1[20] * cell * cell) << "cell 20 is drained";
  EXPECT_GE(left[20], static_cast<float>(settings.cfl_depth)) << "and deep";
  EXPECT_EQ(got[20], 0.0f);
}

}  // namespace
}  // namespace runnel
