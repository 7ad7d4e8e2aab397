// SPDX-License-Identifier: MIT
// The pipe model's bed-load law (pipe.law = "bedload"): the rate against Wong & Parker's formula
// evaluated by hand, the kernel against its C++ reference face by face, the exact balance of bed
// and outflow, and a fixed floor under a sand layer that the flow does not cut.
#include <gtest/gtest.h>

#include <cmath>

#include "runnel/core/parameters_toml.hpp"
#include "runnel/ground/bedload.hpp"
#include "runnel/models/fields.hpp"
#include "runnel/models/parameter_table.hpp"
#include "runnel/models/pipe_model.hpp"
#include "test_support.hpp"

namespace runnel {
namespace {

using test::compute;

Parameters scenario(const std::string& toml) {
  Parameters p = default_parameters();
  read_parameters_toml(p, toml, "test");
  return p;
}

// A dam break over a flat sand bed 0.1 m up: the reservoir's western 2 m filled to `level`.
std::string flume(double level) {
  return "[pipe]\nlaw = \"bedload\"\nflux = \"local-inertial\"\nrain = 0\nevaporation = 0\n"
         "[sediment]\ngrain_diameter = 0.00161\ngrain_density = 2630\nporosity = 0.42\n"
         "[[water.bodies]]\nx0 = 0\nx1 = 2\ny0 = 0\ny1 = 2\nlevel = " +
         std::to_string(level) + "\n";
}

// Vertex (i, j) at map (0.05 i, 2 − 0.05 j): the raster's corner half a cell outside.
Heightmap flat_bed(double height) {
  Heightmap bed(121, 41, 0.05, static_cast<float>(height));
  bed.origin_x = bed.origin_z = -0.025;
  return bed;
}

TEST(Bedload, TheRateIsWongAndParkersMeyerPeterMuller) {
  Parameters p = default_parameters();
  p.set("sediment.grain_diameter", 0.00161);
  p.set("sediment.grain_density", 2630.0);
  const SedimentSettings s = SedimentSettings::from(p);
  // Evaluated by hand for d = 0.1 m, |v| = 1 m/s, n = 0.03: τ = 19.02 Pa, θ = 0.7389,
  // q* = 3.97 (θ − 0.0495)^1.5, q = q* sqrt(1.63 · 9.81 · 0.00161³) = 5.870e-4 m²/s.
  EXPECT_NEAR(bedload_rate(s, 0.03, 9.81, 0.1, 1.0), 5.870e-4, 1e-6);
  // Below the critical Shields stress nothing moves; the rate grows as (θ − θc)^1.5.
  EXPECT_EQ(bedload_rate(s, 0.03, 9.81, 0.1, 0.2), 0.0);  // θ = 0.030
  const double a = bedload_rate(s, 0.03, 9.81, 0.1, 1.0), b = bedload_rate(s, 0.03, 9.81, 0.1, 2.0);
  EXPECT_NEAR(b / a, std::pow((4 * 0.7389 - 0.0495) / (0.7389 - 0.0495), 1.5), 1e-3);
}

TEST(Bedload, TheKernelMovesWhatTheReferenceSaysFaceByFace) {
  // A dam break over a flat erodible bed: after each step the depths and fluxes the kernel read are
  // the state's (the bed load is the step's last stage), so the reference can sum what it should
  // have moved: through each face the water leaves, the rate at the face's speed Q / (l h), h the
  // mean depth of its cells, times l Δt / (1 − p), at most a tenth of the cell's water a step.
  Parameters p = scenario(flume(0.5));
  PipeModel model(compute(), p, flat_bed(0.1));
  const SedimentSettings s = SedimentSettings::from(p);
  const PipeSettings pipe = PipeSettings::from(p);
  const int nx = 121, ny = 41;
  for (int k = 0; k < 200; ++k) model.step();
  double expected = 0;
  long long moved = 0;
  for (int step = 0; step < 50; ++step) {
    const long long before = model.bed_moved_quanta();
    const double dt = model.step();
    moved += model.bed_moved_quanta() - before;
    const std::vector<float> depth = model.depth();
    const std::vector<float> flux = model.state().download_float(kSurfaceWaterOutflux);
    const double quantum_volume = model.state().terrain().volume_quantum(), cell = 0.05;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int k = j * nx + i;
        const int di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
        double cell_load = 0;
        for (int f = 0; f < 4; ++f) {
          const int mi = i + di[f], mj = j + dj[f];
          const bool inside = mi >= 0 && mi < nx && mj >= 0 && mj < ny;
          const int m = mj * nx + mi;
          const double q_out = flux[4 * k + f] - (inside ? flux[4 * m + (f ^ 1)] : 0.0);
          const double h = inside ? 0.5 * (depth[k] + depth[m]) : depth[k];
          if (q_out <= 0 || h <= pipe.cfl_depth) continue;
          const double rate = bedload_rate(s, pipe.manning_n, pipe.gravity, h, q_out / (cell * h));
          cell_load += rate * cell * dt / (1 - s.porosity) / quantum_volume;
        }
        expected += std::min(cell_load, 0.1 * depth[k] * cell * cell / quantum_volume);
      }
  }
  ASSERT_GT(expected, 1e5) << "the flow moves grains";
  EXPECT_NEAR(static_cast<double>(moved), expected, 0.01 * expected);
}

TEST(Bedload, TheBedAndTheOutflowBalanceExactly) {
  Parameters p = scenario(flume(0.5));
  PipeModel model(compute(), p, flat_bed(0.1));
  while (model.time() < 2.0) model.step();
  const MassBalance m = model.mass_balance();
  EXPECT_EQ(m.residual_quanta, 0);
  EXPECT_GT(m.eroded, 0.01);
  EXPECT_GT(model.bed_moved_quanta(), 0);
}

TEST(Bedload, AFixedFloorUnderASandLayerIsNotCut) {
  // 2 mm of sand over a rock floor of erodibility 0 in a closed box: a dam break of 20 cm scours
  // through the sand (7 mm deep where the rock erodes too), never into the rock (within one
  // step's overshoot of the contact: a step's load leaves a cell whose sand is exposed, however
  // little of it is left above the contact).
  Parameters p = scenario(flume(0.3) +
                          "[ground]\nbedrock_erodibility = 0\n"
                          "[[layers]]\nname = \"sand\"\nthickness = 0.002\n");
  p.set("pipe.edges", std::string("closed"));
  PipeModel model(compute(), p, flat_bed(0.1));
  while (model.time() < 2.0) model.step();
  const Heightmap after = model.terrain();
  const float lowest = *std::min_element(after.h.begin(), after.h.end());
  EXPECT_LT(lowest, 0.0985f) << "the flow scours through the sand";
  EXPECT_GT(lowest, 0.098f - 0.0005f) << "the rock 2 mm down holds";
  EXPECT_EQ(model.mass_balance().residual_quanta, 0);
}

}  // namespace
}  // namespace runnel
